// The summary `tspplay info` prints, shared with `tspplay demo`.
#include "cli/info_report.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace tspcli {

using nlohmann::json;

namespace {

// Distribution of the scalar errors over all TSP nodes of one octree level.
struct LevelErrors {
  int octree_nodes = 0;
  int tsp_nodes = 0;
  double es_sum = 0, es_max = 0, et_sum = 0, et_max = 0;
};

std::vector<LevelErrors> errors_by_level(const tsp::TspTree& tree) {
  std::vector<LevelErrors> levels(std::size_t(tree.octree().depth()) + 1);
  for (int o = 0; o < tree.octree().size(); ++o) {
    LevelErrors& l = levels[tree.octree().node(o).level];
    ++l.octree_nodes;
    for (int t = 0; t < tree.time().size(); ++t) {
      const tsp::NodeStats& s = tree.stats(tree.id(o, t));
      ++l.tsp_nodes;
      l.es_sum += s.spatial_error;
      l.et_sum += s.temporal_error;
      l.es_max = std::max(l.es_max, double(s.spatial_error));
      l.et_max = std::max(l.et_max, double(s.temporal_error));
    }
  }
  return levels;
}

json box_json(const tsp::Box& b) {
  return {b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]};
}

}  // namespace

namespace {

// Per LOD level (0 = full resolution): bricks stored, their bytes per step, the level error.
struct LodLevelRow {
  int bricks = 0;
  std::int64_t bytes_per_step = 0;
  double error_sum = 0, error_max = 0;
  std::int64_t error_count = 0;
};

std::vector<LodLevelRow> lod_levels(const tsp::TspTree& tree) {
  const tsp::Octree& o = tree.octree();
  std::vector<LodLevelRow> rows(std::size_t(o.max_lod_level() + 1));
  const auto shape = o.max_brick_samples();
  const std::int64_t brick_bytes = std::int64_t(shape[0]) * shape[1] * shape[2] * 2;
  for (int i = 0; i < o.stored_brick_count(); ++i) {
    const int node = o.stored_brick_node(i);
    LodLevelRow& r = rows[std::size_t(o.lod_level(node))];
    ++r.bricks;
    r.bytes_per_step += brick_bytes;
    if (i < o.brick_count()) continue;
    for (int t = 0; t < tree.time().steps(); ++t) {
      const double e = tree.level_error(node, t);
      r.error_sum += e;
      r.error_max = std::max(r.error_max, e);
      ++r.error_count;
    }
  }
  return rows;
}

}  // namespace

json info_json(const tsp::TspFile& f, bool with_nodes) {
  const tsp::TspTree& tree = f.tree();
  const tsp::Octree& o = tree.octree();
  const tsp::TspMetadata& m = f.metadata();
  const tsp::Dims d = o.dims();
  json j;
  j["file"] = f.path();
  j["file_size"] = std::filesystem::file_size(f.path());
  j["format_version"] = tsp::kTspFormatVersion;
  j["created_by"] = m.created_by;
  j["build_ranks"] = m.build_ranks;
  j["deflate"] = m.deflate;
  j["source"] = m.source;
  j["field"] = m.field;
  j["fields"] = f.fields();
  j["dims"] = {d.x, d.y, d.z};
  j["steps"] = tree.time().steps();
  j["brick"] = o.brick_size();
  j["brick_grid"] = o.brick_grid();
  j["leaf_bricks"] = o.brick_count();
  j["octree_nodes"] = o.size();
  j["octree_depth"] = o.depth();
  j["time_nodes"] = tree.time().size();
  j["tsp_nodes"] = tree.size();
  j["value_range"] = {tree.value_range().lo, tree.value_range().hi};
  j["data_range"] = {m.data_range.lo, m.data_range.hi};
  j["nonfinite_count"] = m.nonfinite_count;
  j["origin"] = m.origin;
  j["spacing"] = m.spacing;
  j["stencil"] = tree.has_stencil();
  j["times"] = m.times;
  j["time_units"] = m.time_units.units;
  j["time_calendar"] = m.time_units.calendar;
  if (tree.has_stencil()) j["inside_fraction"] = tree.inside_fraction(0);
  j["histogram"] = m.histogram;
  json levels = json::array();
  for (const LevelErrors& l : errors_by_level(tree))
    levels.push_back({{"octree_nodes", l.octree_nodes},
                      {"spatial_error_mean", l.tsp_nodes ? l.es_sum / l.tsp_nodes : 0.0},
                      {"spatial_error_max", l.es_max},
                      {"temporal_error_mean", l.tsp_nodes ? l.et_sum / l.tsp_nodes : 0.0},
                      {"temporal_error_max", l.et_max}});
  j["levels"] = levels;
  json lod = json::array();
  for (const LodLevelRow& r : lod_levels(tree))
    lod.push_back({{"bricks", r.bricks},
                   {"bytes_per_step", r.bytes_per_step},
                   {"residual_mean", r.error_count ? r.error_sum / double(r.error_count) : 0.0},
                   {"residual_max", r.error_max}});
  j["lod_levels"] = lod;
  if (with_nodes) {
    json nodes = json::array();
    for (int id = 0; id < tree.size(); ++id) {
      const int oid = tree.octree_of(id);
      const tsp::Span span = tree.time().span(tree.time_of(id));
      const tsp::NodeStats& s = tree.stats(id);
      nodes.push_back({{"id", id},
                       {"octree_id", oid},
                       {"time_id", tree.time_of(id)},
                       {"level", o.node(oid).level},
                       {"box", box_json(o.node(oid).box)},
                       {"span", {span.t0, span.t1}},
                       {"mean", s.mean},
                       {"std", s.std},
                       {"min", s.min},
                       {"max", s.max},
                       {"spatial_error", s.spatial_error},
                       {"temporal_error", s.temporal_error}});
    }
    j["nodes"] = nodes;
  }
  return j;
}

void print_info(const tsp::TspFile& f, bool with_nodes) {
  const tsp::TspTree& tree = f.tree();
  const tsp::Octree& o = tree.octree();
  const tsp::TspMetadata& m = f.metadata();
  const auto g = o.brick_grid();
  const double mib = double(std::filesystem::file_size(f.path())) / (1024.0 * 1024.0);
  std::printf("file          %s (%.2f MiB, format version %d, %s%s)\n", f.path().c_str(), mib,
              o.has_stops() ? tsp::kTspAdaptiveFormatVersion : tsp::kTspFormatVersion,
              m.created_by.c_str(),
              m.build_ranks > 1
                  ? (", built by " + std::to_string(m.build_ranks) + " MPI ranks").c_str()
                  : "");
  std::printf("source        %s\n", m.source.c_str());
  std::printf("field         %s\n", m.field.empty() ? "(unnamed)" : m.field.c_str());
  if (f.fields().size() > 1) {
    std::string names;
    for (const std::string& n : f.fields()) names += (names.empty() ? "" : ", ") + n;
    std::printf("fields        %s (one tree each; --field NAME picks one)\n", names.c_str());
  }
  std::printf("dims          %s voxels\n", tsp::to_string(o.dims()).c_str());
  std::printf("steps         %d\n", tree.time().steps());
  std::printf("brick         %d samples (shared layer included)\n", o.brick_size());
  std::printf("bricks        %d (%d x %d x %d)%s\n", o.brick_count(), g[0], g[1], g[2],
              m.deflate > 0 ? (", deflate level " + std::to_string(m.deflate)).c_str() : "");
  if (o.has_stops()) {
    int reachable = 0, stopped = 0, present = 0;
    for (int i = 0; i < o.size(); ++i) {
      reachable += o.reachable(i);
      stopped += o.stopped(i);
    }
    for (int i = 0; i < o.stored_brick_count(); ++i) present += o.brick_present(i);
    std::printf("adaptive      %d of %d octree nodes hold data, %d stopped above the finest "
                "level (Leven's octree); %d of %d stored bricks present\n",
                reachable, o.size(), stopped, present, o.stored_brick_count());
  }
  std::printf("nodes         %d octree (depth %d) x %d time = %d TSP nodes\n", o.size(), o.depth(),
              tree.time().size(), tree.size());
  std::printf("value range   [%g, %g] (16-bit quantization)\n", tree.value_range().lo,
              tree.value_range().hi);
  std::printf("data range    [%g, %g]\n", m.data_range.lo, m.data_range.hi);
  if (m.nonfinite_count > 0)
    std::printf("non-finite    %lld samples replaced\n", static_cast<long long>(m.nonfinite_count));
  std::printf("geometry      voxel (i,j,k) at (%g, %g, %g) + (i,j,k)*(%g, %g, %g)\n", m.origin[0],
              m.origin[1], m.origin[2], m.spacing[0], m.spacing[1], m.spacing[2]);
  if (!m.times.empty())
    std::printf("times         %s .. %s (physical, from the input%s)\n",
                tsp::format_time(m.times.front(), m.time_units).c_str(),
                tsp::format_time(m.times.back(), m.time_units).c_str(),
                m.time_units.units.empty() ? "" : ("; units " + m.time_units.units +
                                                   (m.time_units.calendar.empty() ? "" : ", calendar " + m.time_units.calendar)).c_str());
  if (tree.has_stencil())
    std::printf("stencil       %.1f%% of the voxels inside the mesh (the rest is never drawn)\n",
                100.0 * tree.inside_fraction(0));
  std::printf("\nscalar errors by octree level (over all time nodes)\n");
  std::printf("  level  nodes   e_ss mean    e_ss max   e_st mean    e_st max\n");
  int level = 0;
  for (const LevelErrors& l : errors_by_level(tree)) {
    std::printf("  %5d  %5d  %10.4g  %10.4g  %10.4g  %10.4g\n", level++, l.octree_nodes,
                l.tsp_nodes ? l.es_sum / l.tsp_nodes : 0.0, l.es_max,
                l.tsp_nodes ? l.et_sum / l.tsp_nodes : 0.0, l.et_max);
  }
  std::printf("\nLOD levels (spec §14; level 0 = the leaf bricks, level k samples every 2^k voxels)\n");
  std::printf("  level  bricks  MiB per step   RMS residual mean   max (data units)\n");
  std::int64_t lod_bytes = 0, leaf_bytes = 0;
  int k = 0;
  for (const LodLevelRow& r : lod_levels(tree)) {
    (k == 0 ? leaf_bytes : lod_bytes) += r.bytes_per_step;
    std::printf("  %5d  %6d  %12.3f   %17.4g   %10.4g\n", k++, r.bricks,
                double(r.bytes_per_step) / (1 << 20),
                r.error_count ? r.error_sum / double(r.error_count) : 0.0, r.error_max);
  }
  std::printf("  levels above 0 add %.1f%% to the bricks\n",
              leaf_bytes ? 100.0 * double(lod_bytes) / double(leaf_bytes) : 0.0);
  if (!with_nodes) return;
  std::printf(
      "\n      id  octree  level  span        mean         std         min         max"
      "      e_ss      e_st\n");
  for (int id = 0; id < tree.size(); ++id) {
    const int oid = tree.octree_of(id);
    const tsp::Span span = tree.time().span(tree.time_of(id));
    const tsp::NodeStats& s = tree.stats(id);
    std::printf(
        "%8d  %6d  %5d  [%d,%d]%*s %11.5g %11.5g %11.5g %11.5g %9.4g %9.4g\n", id, oid,
        o.node(oid).level, span.t0, span.t1,
        std::max(0, 8 - int(std::to_string(span.t0).size() + std::to_string(span.t1).size())), "",
        s.mean, s.std, s.min, s.max, s.spatial_error, s.temporal_error);
  }
}

}  // namespace tspcli
