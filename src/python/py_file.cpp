// tspplay._core.TspFile: an open .tsp file — what `tspplay info` reports, every TSP node's
// statistics as numpy columns, a step's samples, and `tspplay metrics`' per-node errors.
#include <memory>
#include <string>
#include <vector>

#include "cli/info_report.h"
#include "py_common.h"
#include "tsp/core/error.h"
#include "tsp/core/parallel_for.h"
#include "tsp/core/stopwatch.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/metric/tf_io.h"
#include "tsp/store/tsp_file.h"
#include "tsp/tree/stats_columns.h"

namespace tsppy {
namespace {

// A numpy array of n values of T that owns v (no copy).
template <class T>
py::array column(std::vector<T>&& v) {
  auto* owned = new std::vector<T>(std::move(v));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>({py::ssize_t(owned->size())}, {py::ssize_t(sizeof(T))}, owned->data(),
                        owner);
}

// A numpy array (n, k) of T owning v (n·k values, row-major).
template <class T>
py::array table(std::vector<T>&& v, py::ssize_t k) {
  auto* owned = new std::vector<T>(std::move(v));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  const py::ssize_t n = py::ssize_t(owned->size()) / k;
  return py::array_t<T>({n, k}, {py::ssize_t(sizeof(T)) * k, py::ssize_t(sizeof(T))},
                        owned->data(), owner);
}

// Every TSP node's statistics, by node id, as columns.
py::dict nodes_of(const tsp::TspFile& f) {
  const tsp::TspTree& tree = f.tree();
  const tsp::Octree& o = tree.octree();
  const std::size_t n = std::size_t(tree.size());
  std::vector<std::int32_t> octree_id(n), time_id(n), level(n), t0(n), t1(n), box(6 * n);
  for (int id = 0; id < tree.size(); ++id) {
    const std::size_t i = std::size_t(id);
    const int oid = tree.octree_of(id);
    const tsp::Span span = tree.time().span(tree.time_of(id));
    const tsp::Box& b = o.node(oid).box;
    octree_id[i] = oid;
    time_id[i] = tree.time_of(id);
    level[i] = o.node(oid).level;
    t0[i] = span.t0;
    t1[i] = span.t1;
    for (int a = 0; a < 3; ++a) {
      box[6 * i + std::size_t(a)] = b.lo[std::size_t(a)];
      box[6 * i + 3 + std::size_t(a)] = b.hi[std::size_t(a)];
    }
  }
  tsp::StatsColumns stats = tsp::stats_columns(tree);
  py::dict d;
  d["octree_id"] = column(std::move(octree_id));
  d["time_id"] = column(std::move(time_id));
  d["level"] = column(std::move(level));
  d["t0"] = column(std::move(t0));
  d["t1"] = column(std::move(t1));
  d["box"] = table(std::move(box), 6);
  d["mean"] = column(std::move(stats.mean));
  d["std"] = column(std::move(stats.std));
  d["min"] = column(std::move(stats.min));
  d["max"] = column(std::move(stats.max));
  d["spatial_error"] = column(std::move(stats.spatial_error));
  d["temporal_error"] = column(std::move(stats.temporal_error));
  return d;
}

// Step t's samples (z, y, x) as float32, decoded from the leaf bricks (16-bit codes over the
// file's value range). Runs without the GIL.
std::vector<float> step_samples(const tsp::TspFile& f, int t) {
  const tsp::TspTree& tree = f.tree();
  const tsp::Octree& o = tree.octree();
  if (o.has_stops())
    throw tsp::UsageError(f.path() + ": an adaptive octree (build --octree-error) holds no "
                          "full-resolution grid to read a step from");
  if (t < 0 || t >= tree.time().steps())
    throw tsp::UsageError("step " + std::to_string(t) + ": " + f.path() + " has steps 0.." +
                          std::to_string(tree.time().steps() - 1));
  const tsp::Dims d = o.dims();
  std::vector<float> out(std::size_t(d.count()));
  const tsp::Quantizer q{tree.value_range()};
  tsp::parallel_for(o.brick_count(), 1, 0, [&](int, std::int64_t begin, std::int64_t end) {
   for (std::int64_t b = begin; b < end; ++b) {
    const tsp::BrickLattice l = o.lattice(int(b));
    std::vector<std::uint16_t> codes(std::size_t(l.count()));
    f.read_brick(int(b), t, codes);
    std::size_t k = 0;
    for (int z = 0; z < l.samples[2]; ++z)
      for (int y = 0; y < l.samples[1]; ++y)
        for (int x = 0; x < l.samples[0]; ++x, ++k) {
          const std::int64_t gx = l.origin[0] + x, gy = l.origin[1] + y, gz = l.origin[2] + z;
          out[std::size_t((gz * d.y + gy) * d.x + gx)] = q.decode(codes[k]);
        }
   }
  });
  return out;
}

}  // namespace

void bind_file(py::module_& m) {
  py::class_<tsp::TspFile>(m, "TspFile",
                           "An open .tsp file (read-only; reads are thread-safe).")
      .def(py::init([](const std::string& path, const std::string& field) {
             py::gil_scoped_release release;
             return tsp::TspFile::open(path, field);
           }),
           py::arg("path"), py::arg("field") = "",
           "Opens path (field: one of its fields, '' the first). Raises IoError, FormatError, "
           "UsageError (no such field).")
      .def_property_readonly("path", &tsp::TspFile::path)
      .def_property_readonly("fields", &tsp::TspFile::fields)
      .def_property_readonly("field", [](const tsp::TspFile& f) {
        return f.fields()[std::size_t(f.field_index())];
      })
      .def("info", [](const tsp::TspFile& f) { return to_python(tspcli::info_json(f, false)); },
           "What `tspplay info --json` prints (dims, steps, times, ranges, levels, ...).")
      .def("nodes", &nodes_of,
           "Every TSP node's statistics by node id as numpy columns (as `info --nodes`).")
      .def(
          "step",
          [](const tsp::TspFile& f, int t) {
            std::vector<float> v;
            {
              py::gil_scoped_release release;
              v = step_samples(f, t);
            }
            const tsp::Dims d = f.tree().octree().dims();
            py::array a = column(std::move(v));
            return a.attr("reshape")(py::make_tuple(d.z, d.y, d.x));
          },
          py::arg("t"),
          "Step t's samples as float32 (z, y, x), decoded from the 16-bit bricks. Raises "
          "UsageError (no such step), IoError, FormatError.")
      .def(
          "metrics",
          [](const tsp::TspFile& f, const std::string& tf_arg, const std::string& metric_name,
             int entries, int threads) {
            const tsp::Metric metric = tsp::parse_metric(metric_name);
            const tsp::TspTree& tree = f.tree();
            const tsp::ValueHistogram histogram = tsp::histogram_of(f);
            const tsp::TransferFunction tf = tsp::transfer_function_from_arg(
                tf_arg, tree.value_range(), entries, {}, &histogram);
            const int used = tsp::resolve_threads(threads);
            tsp::MetricResult r;
            double ms = 0;
            {
              py::gil_scoped_release release;
              const tsp::Stopwatch watch;
              r = tsp::compute_errors(metric, tree, tf, &f, used);
              ms = watch.ms();
            }
            std::vector<float> colours;
            for (const tsp::Rgba& c : r.mean_colour)
              colours.insert(colours.end(), {c.r, c.g, c.b, c.a});
            py::dict d;
            d["metric"] = tsp::to_string(metric);
            d["recompute_ms"] = ms;
            d["threads"] = used;
            d["tf_range"] = py::make_tuple(tf.domain().lo, tf.domain().hi);
            d["spatial_error"] = column(std::move(r.errors.spatial));
            d["temporal_error"] = column(std::move(r.errors.temporal));
            d["transparent"] = column(std::vector<std::uint8_t>(r.transparent)).attr("astype")("bool");
            d["mean_colour"] = table(std::move(colours), 4);
            return d;
          },
          py::arg("tf"), py::arg("metric") = "approximate", py::arg("entries") = 256,
          py::arg("threads") = 0,
          "`tspplay metrics`: one error metric recomputed for a TF (a file or preset:NAME), per "
          "TSP node. Raises UsageError, IoError, FormatError.");
}

}  // namespace tsppy
