#include "tsp/frame/frame_plan.h"

#include "tsp/core/error.h"

#include <cassert>
#include <cmath>

namespace tsp {

namespace {
// Any view: which nodes a traversal emits does not depend on the order it visits them in.
const ViewOrder kAnyView = ViewOrder::orthographic({1, 1, 1});

void collect_leaves(const Octree& octree, int id, const ViewOrder& view, std::vector<int>& out) {
  const OctreeNode& n = octree.node(id);
  if (n.is_leaf()) {
    out.push_back(n.brick);
    return;
  }
  const ChildOrder order = back_to_front_children(octree, id, view);
  for (int i = 0; i < order.count; ++i) collect_leaves(octree, order.ids[i], view, out);
}
}  // namespace

const char* to_string(DrawClass c) {
  switch (c) {
    case DrawClass::not_rendered:
      return "not_rendered";
    case DrawClass::untextured:
      return "untextured";
    case DrawClass::reused_texture:
      return "reused_texture";
    case DrawClass::new_texture:
      return "new_texture";
    case DrawClass::clipped:
      return "clipped";
  }
  return "?";
}

NodeInfoFn node_info(const MetricResult& m) {
  return [&m](int id) { return NodeClassInfo{m.errors.spatial[id], m.transparent[id] != 0}; };
}

NodeInfoFn node_info(const FrameMetric& m) {
  return [&m](int id) { return m.class_info(id); };
}

Shading shading_of(const NodeClassInfo& info, const Tolerances& tol) {
  if (info.transparent) return Shading::none;
  if (info.spatial <= tol.spatial) return Shading::flat;  // false for NaN: textured
  return Shading::textured;
}

Shading node_shading(const TspTree& tree, int id, const NodeClassInfo& info, const Tolerances& tol) {
  const Shading s = shading_of(info, tol);
  if (s == Shading::flat && tree.inside_fraction(tree.octree_of(id)) < 1.f) return Shading::textured;
  return s;
}

std::int64_t texture_bytes(const Octree& octree, const TextureKey& key) {
  return octree.lattice(key.brick).count() * std::int64_t(sizeof(std::uint16_t));
}

std::vector<int> leaf_bricks(const Octree& octree, int id, const ViewOrder& view) {
  std::vector<int> out;
  collect_leaves(octree, id, view, out);
  return out;
}

std::vector<int> node_bricks(const Octree& octree, int id, const ViewOrder& view, LodStops stops) {
  if (!octree.node(id).is_leaf() && !stops.empty() && stops[std::size_t(id)] != LodStop::none)
    return {octree.node_brick(id)};
  return leaf_bricks(octree, id, view);
}

Shading emitted_shading(const TspTree& tree, const Emitted& e, const NodeClassInfo& info,
                        const Tolerances& tol, LodStops stops, bool clip_surface) {
  if (e.clip == ClipSide::removed) return Shading::none;
  Shading s = node_shading(tree, tree.id(e.octree_id, e.time_id), info, tol);
  // A splat (tsp/lod/splat_cut.h): its mean colour and opacity, never a texture.
  const bool splat = !stops.empty() && stops[std::size_t(e.octree_id)] == LodStop::splat;
  if (s == Shading::textured && e.clip != ClipSide::straddles && splat) s = Shading::flat;
  // Across the clip surface: clipped per sample, which a flat node (drawn whole) cannot be.
  if (e.clip == ClipSide::straddles && (s == Shading::flat || (clip_surface && s == Shading::none)))
    s = Shading::textured;
  return s;
}

TextureKey texture_key(const Octree& octree, int brick, int t0) {
  return TextureKey{brick, t0,
                    brick < octree.brick_count() ? 0 : octree.lod_level(octree.stored_brick_node(brick))};
}

TextureKey span_texture_key(const Octree& octree, int brick, const Span& span, SpanStep r) {
  if (r != SpanStep::mean || span.t1 == span.t0)
    return texture_key(octree, brick, representative_step(span, r));
  TextureKey k = texture_key(octree, brick, span.t0);
  k.t1 = span.t1;
  return k;
}

const char* to_string(SpanStep s) {
  return s == SpanStep::middle ? "middle" : s == SpanStep::mean ? "mean" : "first";
}

SpanStep parse_span_step(const std::string& text, const std::string& option) {
  if (text == "first") return SpanStep::first;
  if (text == "middle") return SpanStep::middle;
  if (text == "mean") return SpanStep::mean;
  throw UsageError(option + " " + text + ": expected first, middle or mean");
}

double FramePlan::percent(DrawClass c) const {
  if (total_voxels == 0) return 0;
  return 100.0 * double(class_voxels[int(c)]) / double(total_voxels);
}

FramePlan plan_frame(const FramePlanQuery& q, TextureCache& cache) {
  const TspTree& tree = q.tree;
  const int step = q.step;
  const Tolerances& tol = q.tol;
  const LodStops stops = q.stops;
  const std::int64_t upload_budget = q.upload_budget;
  const Octree& octree = tree.octree();
  FramePlan plan;
  plan.step = step;
  plan.nodes.reserve(q.emitted.size());
  cache.begin_frame();
  for (const Emitted& e : q.emitted) {
    assert(e.span.contains(step) && "emitted span must hold the frame's step");
    PlannedNode p;
    p.node = e;
    p.voxels = octree.node(e.octree_id).box.count();
    const Shading shading = emitted_shading(tree, e, q.info(tree.id(e.octree_id, e.time_id)), tol,
                                            stops, q.clip_surface);
    if (e.clip == ClipSide::removed) {
      p.cls = DrawClass::clipped;
    } else if (shading == Shading::none) {
      p.cls = DrawClass::not_rendered;
    } else if (shading == Shading::flat) {
      p.cls = DrawClass::untextured;
    } else {
      p.first_texture = int(plan.textures.size());
      bool uploaded = false;
      for (int brick : node_bricks(octree, e.octree_id, q.view, stops)) {
        const TextureKey key = span_texture_key(octree, brick, e.span, q.span_step);
        const std::int64_t bytes = texture_bytes(octree, key);
        if (upload_budget > 0 && plan.uploads > 0 && !cache.contains(key) &&
            plan.bytes_uploaded + bytes > upload_budget) {
          PlannedTexture deferred{key, bytes, false};
          deferred.deferred = true;
          plan.textures.push_back(deferred);
          ++plan.deferred;
          uploaded = true;  // drawn as new data once it arrives
          continue;
        }
        TextureRequest r = cache.request(key, bytes);
        plan.evict_before.insert(plan.evict_before.end(), r.evicted.begin(), r.evicted.end());
        plan.textures.push_back(PlannedTexture{key, bytes, !r.hit});
        if (!r.hit) {
          uploaded = true;
          ++plan.uploads;
          plan.bytes_uploaded += bytes;
        }
      }
      p.texture_count = int(plan.textures.size()) - p.first_texture;
      p.cls = uploaded ? DrawClass::new_texture : DrawClass::reused_texture;
    }
    plan.class_voxels[int(p.cls)] += p.voxels;
    plan.total_voxels += p.voxels;
    plan.nodes.push_back(p);
  }
  plan.release_after = cache.end_frame();
  plan.textures_resident = cache.stats().resident_count;
  plan.texture_bytes = cache.stats().resident_bytes;
  return plan;
}

TextureKeySet reachable_textures(const TspTree& tree, const NodeErrors& errors,
                                 const NodeInfoFn& info, const Tolerances& tol,
                                 bool skip_transparent, SpanStep span_step, LodStops stops) {
  TextureKeySet keys;
  TransparentFn transparent;
  if (skip_transparent) transparent = [&info](int id) { return info(id).transparent; };
  for (int t = 0; t < tree.time().steps(); ++t) {
    const TraversalQuery query{.tree = tree,
                               .step = t,
                               .tol = tol,
                               .errors = errors,
                               .view = kAnyView,
                               .stops = stops,
                               .transparent = transparent};
    for (const Emitted& e : traverse(query)) {
      if (emitted_shading(tree, e, info(tree.id(e.octree_id, e.time_id)), tol, stops) !=
          Shading::textured)
        continue;
      for (int brick : node_bricks(tree.octree(), e.octree_id, kAnyView, stops))
        keys.insert(span_texture_key(tree.octree(), brick, e.span, span_step));
    }
  }
  return keys;
}

TextureKeySet reachable_textures(const TspTree& tree, const MetricResult& m, const Tolerances& tol,
                                 bool skip_transparent, SpanStep span_step, LodStops stops) {
  return reachable_textures(tree, m.errors, node_info(m), tol, skip_transparent, span_step, stops);
}

TextureKeySet reachable_textures(const TspTree& tree, FrameMetric& m, const Tolerances& tol,
                                 bool skip_transparent, SpanStep span_step, LodStops stops) {
  const NodeErrors& errors = m.all_errors();
  return reachable_textures(tree, errors, node_info(m), tol, skip_transparent, span_step, stops);
}

}  // namespace tsp
