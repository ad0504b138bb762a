// The LOD controller (paper 000 §5): keeps an active cut from frame to frame and adapts it to a
// frame-time target with a split queue (non-leaf cut nodes, largest error first) and a merge queue
// (parents of cut nodes, smallest error first), bounded per frame, by the texture budget and by the
// cost model's prediction. Without a target (0) it refines every node whose error is above
// min_error, split_limit nodes per frame: the progressive refinement to full quality when idle.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "tsp/frame/camera.h"
#include "tsp/lod/cost_model.h"
#include "tsp/lod/lod_cut.h"
#include "tsp/lod/splat_cut.h"
#include "tsp/tree/traversal.h"
#include "tsp/lod/lod_error.h"
#include "tsp/metric/transfer_function.h"
#include "tsp/tree/tsp_tree.h"

namespace tsp {

/// What the controller does when even the coarsest cut misses the target.
enum class LodFallback {
  scale,   ///< a smaller render target (down to a quarter per axis), upscaled
  splats,  ///< a splat cut (tsp/lod/splat_cut.h) at full size, its minimum splat size adapted
};

/// "scale" or "splats". Never throws.
const char* to_string(LodFallback f);
/// Parses "scale" or "splats"; throws UsageError naming option otherwise.
LodFallback parse_lod_fallback(const std::string& text, const std::string& option);

/// What bounds the controller.
struct LodOptions {
  double target_ms = 0;          ///< frame-time target; 0: refine to min_error regardless of time
  int split_limit = 8;           ///< splits per frame (a split costs uploads: RAM → texture)
  int merge_limit = 16;          ///< merges per frame
  std::int64_t texture_budget = 0;  ///< bytes the cut's bricks may hold (0: unlimited)
  /// Nodes below this error (pixels × ΔE) are not split, unless timed with the frame under the
  /// target's band (time left over refines them too).
  double min_error = 0.25;
  /// Centre of attention (voxels): when set, errors are weighted by distance from it and by
  /// distance from the image centre (paper 002); unset, every pixel counts alike.
  std::optional<std::array<double, 3>> focus;
  /// When even the coarsest cut misses the target (timed only).
  LodFallback fallback = LodFallback::scale;
};

/// What one update did, for frames.json.
struct LodFrameStats {
  int cut_size = 0;
  std::vector<int> nodes_per_level;  ///< index = LOD level
  int splits = 0, merges = 0;
  std::int64_t texture_bytes = 0;    ///< the cut's bricks (one per node) at 2 bytes per sample
  double cost = 0;                   ///< Σ cost over the cut
  double predicted_ms = 0;           ///< the cost model's prediction (0 before the first frame)
  double max_error = 0;              ///< the largest error left among splittable cut nodes
  /// Render-target share per axis for the frame (1 unless even the root misses the target).
  double render_scale = 1;
  /// Splat fallback: the minimum splat size in pixels and the splats drawn (0: textured cut).
  double splat_px = 0;
  int splats = 0;
};

/// LodFrameStats as JSON, one key per field with the field's name (frames.json's "lod", the
/// player's stats). Never throws but std::bad_alloc.
void to_json(nlohmann::json& j, const LodFrameStats& s);

/// A cut's size, nodes per level and texture bytes (the rest zero: no update made it). Never
/// throws.
LodFrameStats cut_stats(const LodCut& cut);

/// One active cut and its controller. Not thread-safe.
class LodController {
 public:
  /// Starts from the coarsest cut (the root). tree must outlive it.
  LodController(const TspTree& tree, LodOptions options);
  /// Adapts the cut for the next frame of step t under camera, tf and sample spacing, and returns
  /// what it did; nodes clip marks removed (a probe's, tsp/clip) cost nothing and never split.
  /// Never throws.
  LodFrameStats update(const Camera& camera, int t, const TransferFunction& tf, double spacing,
                       ClipSides clip = {});
  /// The measured time of the frame drawn with the last update's cut, without its texture
  /// uploads (bounded separately by split_limit); fits the cost model.
  void measured(double ms);
  /// Changes the target (0: refine fully, as when the player is idle).
  void set_target(double ms) { options_.target_ms = ms; }
  /// The options in use.
  const LodOptions& options() const { return options_; }
  /// Replaces the options from the next update on (the cut and the cost model stay).
  void set_options(LodOptions o) { options_ = std::move(o); }
  /// The cut.
  const LodCut& cut() const { return cut_; }
  /// What the next frame draws: the splat cut's stops while splatting, else the cut's.
  LodStops stops() const { return splatting_ ? LodStops(splat_.stops) : cut_.stops(); }
  /// True while the splat fallback is in use.
  bool splatting() const { return splatting_; }
  /// The cost of node o in the last update: pixels × samples over its leaf bricks that are not
  /// culled or transparent (a small share for those), divided by its sample step multiplier.
  double node_cost(int o) const { return cost_[std::size_t(o)]; }
  /// The stored bricks the next splits are likely to need: the children of the n splittable cut
  /// nodes with the largest errors in the last update, most likely first (for prefetching).
  std::vector<int> likely_split_bricks(int n) const;
  /// Render-target share per axis the last update chose.
  double render_scale() const { return scale_; }

 private:
  const TspTree& tree_;
  LodOptions options_;
  LodCut cut_;
  CostModel model_;
  std::vector<double> error_, cost_;
  double last_cost_ = -1;
  double last_ms_ = 0;   // the last measured frame
  double scale_ = 1;
  double scale_of_last_ = 1;  // the scale the last measured frame was drawn at
  double scale_of_frame_ = 1; // the scale the last update chose
  bool last_coarsest_ = false;  // the last update left the root alone
  // The splat fallback: on while the coarsest textured cut would miss the target.
  bool splatting_ = false;       // (also: the frame of the last update was a splat frame)
  SplatCut splat_;               // the last update's splat cut
  double splat_budget_ = 0;      // screen area the splat cut may cover (splat_cut_within)
  int splat_hold_ = 0;           // frames left before the splat cut may refine again
  double splat_ms_ = 0, splat_area_ = 0;  // the last measured splat frame and its Σ area
  double coarsest_ms_ = 0, coarsest_cost_ = 0;  // the last measured coarsest textured frame
  void adapt_scale(bool coarsest);
  void adapt_splats(ClipSides clip);
  std::vector<NodeProjection> proj_;  // every node's projection in the last update's view
  void evaluate(const Camera& camera, int t, const TransferFunction& tf,
                const TfColourSlopes& slopes, double spacing, ClipSides clip);
};

}  // namespace tsp
