// tsp/frame: everything a frame decides without GL (camera, plan, texture-cache policy, slicers);
// may include core/, tree/ and metric/.
// The per-frame plan (spec §5 classes, paper Table 5): how each node the traversal emitted for a
// step is drawn — not at all (NR), as flat polygons (UP), or from a brick texture that is resident
// (RT) or uploaded now (NT) — which textures to upload and delete, and the class shares by voxels.
// Pure logic: the renderer carries the plan out with GL. Rules: docs/caching.md.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "tsp/frame/texture_cache.h"
#include "tsp/metric/frame_metric.h"
#include "tsp/metric/metric.h"
#include "tsp/tree/traversal.h"
#include "tsp/tree/tsp_tree.h"

namespace tsp {

/// The paper's Table-5 classes, in report order.
/// clipped: removed by a clip probe (tsp/clip), drawn nowhere and never uploaded (issue 14).
enum class DrawClass : std::uint8_t { not_rendered, untextured, reused_texture, new_texture, clipped };
/// Number of DrawClass values.
inline constexpr int kDrawClassCount = 5;
/// "not_rendered", "untextured", "reused_texture", "new_texture" or "clipped" (the frames.json
/// names).
const char* to_string(DrawClass c);

/// Which step's data textures a span (spec §5; the paper uses the first).
enum class SpanStep {
  first,   ///< t0, the paper's rule
  middle,  ///< ⌊(t0 + t1)/2⌋: at most half the span away from any step it stands for
  mean,    ///< the per-voxel mean of steps t0..t1, computed when first needed (what the
           ///< temporal error measures deviation from)
};
/// "first", "middle" or "mean".
const char* to_string(SpanStep s);
/// Parses "first", "middle" or "mean"; throws UsageError naming `option` and the text.
SpanStep parse_span_step(const std::string& text, const std::string& option);
/// The step whose bricks texture span s under rule r (mean: the middle step, which stands for
/// the span where one step is needed, such as its stencil).
inline int representative_step(const Span& s, SpanStep r) {
  return r == SpanStep::first ? s.t0 : s.t0 + (s.t1 - s.t0) / 2;
}

/// How a node is shaded, before the cache decides between RT and NT.
enum class Shading { none, flat, textured };

/// Looks up a TSP node id's NodeClassInfo (from a FrameMetric, or a table in tests).
using NodeInfoFn = std::function<NodeClassInfo(int tsp_id)>;
/// A NodeInfoFn reading m, which must outlive it.
NodeInfoFn node_info(const MetricResult& m);
/// A NodeInfoFn reading m.class_info, m outliving it.
NodeInfoFn node_info(const FrameMetric& m);

/// none for a transparent node, flat when e_s ≤ tol.spatial, textured otherwise (also for NaN).
Shading shading_of(const NodeClassInfo& info, const Tolerances& tol);
/// shading_of for TSP node id of tree, except that a node partly outside a stencil is never
/// drawn flat (its box would cover the outside): textured instead. Never throws.
Shading node_shading(const TspTree& tree, int id, const NodeClassInfo& info, const Tolerances& tol);
/// How emitted node e is drawn (info: its TSP node's class): none when clipped away; else
/// node_shading, except that a splat (LodStop::splat in stops) is drawn flat, never textured, and a
/// node across the clip surface is textured where it would be flat — or, with clip_surface, not
/// drawn — since only samples can be clipped. The one rule for planning, uploads and reachability.
/// Never throws.
Shading emitted_shading(const TspTree& tree, const Emitted& e, const NodeClassInfo& info,
                        const Tolerances& tol, LodStops stops = {}, bool clip_surface = false);

/// Bytes of a brick texture: 2 per stored sample (16-bit scalars, R16); key.brick is a stored
/// brick (leaf or level).
std::int64_t texture_bytes(const Octree& octree, const TextureKey& key);

/// Leaf bricks below octree node id (the node's own brick for a leaf) in back-to-front order.
std::vector<int> leaf_bricks(const Octree& octree, int id, const ViewOrder& view);

/// The stored bricks that texture emitted node id: its level brick when it is an internal node
/// marked in stops (an LOD cut node), otherwise its leaf bricks back-to-front.
std::vector<int> node_bricks(const Octree& octree, int id, const ViewOrder& view, LodStops stops);
/// The texture key of stored brick `brick` at step t0 (level: the brick's LOD level).
TextureKey texture_key(const Octree& octree, int brick, int t0);
/// The key of brick's texture for span under rule r: texture_key(octree, brick,
/// representative_step(span, r)), or for SpanStep::mean over a span of several steps the key of
/// its mean (t0, t1 the span's).
TextureKey span_texture_key(const Octree& octree, int brick, const Span& span, SpanStep r);

/// One emitted node and how to draw it.
struct PlannedNode {
  Emitted node;
  DrawClass cls = DrawClass::not_rendered;
  std::int64_t voxels = 0;  ///< node.box.count() of the octree node
  int first_texture = 0;    ///< its textures: FramePlan::textures[first, first + count)
  int texture_count = 0;    ///< 0 unless RT/NT; the leaf bricks back-to-front for an internal node
};

/// One texture a node draws with.
struct PlannedTexture {
  TextureKey key;
  std::int64_t bytes = 0;
  bool upload = false;    ///< not resident: create and fill it before drawing
  bool deferred = false;  ///< over the frame's upload budget: not resident, not uploaded now
};

/// Everything the renderer needs for one frame. GL order: delete evict_before, draw `nodes`
/// in order (uploading textures marked upload), then delete release_after.
struct FramePlan {
  int step = 0;
  std::vector<PlannedNode> nodes;        ///< as emitted: back to front
  std::vector<PlannedTexture> textures;  ///< per textured node, see PlannedNode
  std::vector<TextureKey> evict_before;  ///< evicted to make room (may include keys uploaded again)
  std::vector<TextureKey>
      release_after;  ///< deleted at the end of the frame (cache policy, budget)
  std::array<std::int64_t, kDrawClassCount> class_voxels{};  ///< voxels per DrawClass
  std::int64_t total_voxels = 0;       ///< sum of class_voxels (the grid's voxel count)
  std::int64_t uploads = 0;            ///< textures uploaded this frame
  std::int64_t deferred = 0;           ///< textures left to later frames (upload budget)
  std::int64_t bytes_uploaded = 0;     ///< their bytes
  std::int64_t textures_resident = 0;  ///< resident after the frame
  std::int64_t texture_bytes = 0;      ///< their bytes
  /// Share of the voxels in class c, in percent (the four sum to 100 up to rounding).
  double percent(DrawClass c) const;
};

/// What one frame plan reads besides the cache: the tree, the step, the traversal's output for
/// it, the node classes, the tolerances, the view and the knobs. tree, emitted and what info
/// reads must outlive the call.
struct FramePlanQuery {
  const TspTree& tree;                    ///< the tree the traversal walked
  int step = 0;                           ///< the frame's step
  std::span<const Emitted> emitted;       ///< traverse()'s output for step (every span holds it)
  NodeInfoFn info;                        ///< each TSP node's class
  Tolerances tol;                         ///< the traversal's tolerances
  ViewOrder view;                         ///< orders an internal node's leaf bricks
  std::int64_t upload_budget = 0;         ///< bytes uploaded per frame at most; 0: no limit
  SpanStep span_step = SpanStep::middle;  ///< which step's data textures a span
  LodStops stops = {};                    ///< the LOD cut the traversal used (empty: none)
  bool clip_surface = false;              ///< the clip surface shows the data on it
};

/// Plans the frame of q.step from the traversal's output q.emitted (every span must hold
/// step): classifies each node, requests the textures of RT/NT nodes from cache inside one
/// begin_frame()/end_frame(), and counts voxels per class. A node that is textured is drawn by
/// the textures span_texture_key(brick, span, span_step) of node_bricks(…, stops)
/// (equal keys hold equal data, whichever span made them), ordered back-to-front by view;
/// it is NT when any of them is uploaded now (or deferred), RT otherwise. With upload_budget > 0,
/// a texture not resident whose upload would take the frame's uploads over upload_budget bytes
/// is deferred — not requested from the cache, so it stays absent until a later frame uploads it
/// — except the frame's first upload, which always goes ahead so that repeated frames of one step
/// complete. The renderer draws deferred bricks flat in their node's mean colour. A node the
/// traversal clipped away (Emitted::clip 1) is class clipped and uploads nothing; one across
/// the clip surface (clip 2) is textured where it would be flat — and, with clip_surface (the
/// surface shows the data on it), where it would be transparent too. Asserts the cache has no
/// open frame; throws what q.info throws.
FramePlan plan_frame(const FramePlanQuery& q, TextureCache& cache);

/// Every texture key some step's frame could draw under errors, info and tol — the set to keep
/// with TextureCache::drop_unreachable after a tolerance change (stops: the LOD cut in use;
/// skip_transparent: the traversal's transparency rule, as RenderSettings::skip_transparent).
/// Costs one traversal per step. Throws what info throws.
TextureKeySet reachable_textures(const TspTree& tree, const NodeErrors& errors,
                                 const NodeInfoFn& info, const Tolerances& tol,
                                 bool skip_transparent, SpanStep span_step = SpanStep::middle,
                                 LodStops stops = {});
/// Same, with the errors and classes of m.
TextureKeySet reachable_textures(const TspTree& tree, const MetricResult& m, const Tolerances& tol,
                                 bool skip_transparent, SpanStep span_step = SpanStep::middle,
                                 LodStops stops = {});
/// Same, with every node of m made current (FrameMetric::all_errors). Throws what m throws.
TextureKeySet reachable_textures(const TspTree& tree, FrameMetric& m, const Tolerances& tol,
                                 bool skip_transparent, SpanStep span_step = SpanStep::middle,
                                 LodStops stops = {});

}  // namespace tsp
