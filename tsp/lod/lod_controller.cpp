#include "tsp/lod/lod_controller.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <queue>

#include "tsp/core/error.h"

namespace tsp {

namespace {
// A transparent, uniform or culled leaf still costs its pixels a ray step or two: this share of
// a textured leaf's cost.
constexpr double kEmptyCostShare = 0.02;
// A swap (merge one node to afford a split) happens only when the split's error is this many
// times the merge's, so the cut does not oscillate between equals.
constexpr double kSwapGain = 2.0;
// The render scale drops when the coarsest cut takes longer than kScaleDownAt × target, and
// rises when a frame takes less than kScaleUpAt × target; never below kMinScale.
constexpr double kScaleDownAt = 1.1, kScaleUpAt = 0.8, kMinScale = 0.25;
// The splat cut grows by at most this factor in nodes, or one split (kChildrenPerSplit − 1
// more nodes), from one frame to the next.
constexpr double kMaxSplatGrowth = 1.25;
constexpr int kChildrenPerSplit = 8;
// After a splat frame over the band the cut stays coarser this many frames before it may refine.
constexpr int kSplatHoldFrames = 8;
// Frames predicted within this share of the target leave the cut as it is; a merge that would
// fall below the band waits until a frame is kFarOver × the target.
constexpr double kDeadBand = 0.1, kFarOver = 1.25;
// Predictions blend the last frame moved by the slope (this share) with the fitted model (the
// rest): the last frame alone follows every spike, the model alone lags a view change.
constexpr double kAnchorShare = 0.5;
// The most one frame's splits may add to the cost, as a share of the drawn frame's.
constexpr double kMaxGrowth = 0.25;
}  // namespace

LodController::LodController(const TspTree& tree, LodOptions options)
    : tree_(tree),
      options_(std::move(options)),
      cut_(tree.octree()),
      error_(std::size_t(tree.octree().size()), 0),
      cost_(std::size_t(tree.octree().size()), 0) {}

void LodController::evaluate(const Camera& camera, int t, const TransferFunction& tf,
                             const TfColourSlopes& slopes, double spacing, ClipSides clip) {
  const Octree& o = tree_.octree();
  const Dims d = o.dims();
  const std::array<double, 3> focus =
      options_.focus.value_or(std::array<double, 3>{0.5 * (d.x - 1), 0.5 * (d.y - 1), 0.5 * (d.z - 1)});
  const double diagonal = std::hypot(double(d.x), double(d.y), double(d.z));
  proj_ = project_nodes(o, camera);
  const std::vector<NodeProjection>& proj = proj_;
  std::vector<NodeProjection> leaves(std::size_t(o.brick_count()));
  // Per leaf brick, its finest node's projection (below a stop too: those nodes keep their boxes).
  for (int b = 0; b < o.brick_count(); ++b) leaves[std::size_t(b)] = proj[std::size_t(o.brick_node(b))];
  const std::vector<double> leaf_vis = leaf_visibility(tree_, t, camera, leaves, tf);
  // Full-resolution sample cost and visible area of each leaf brick, summed bottom-up (children
  // follow their parents in node order); a node's cost is its leaves' over its sample step
  // multiplier (the ray caster skips transparent leaf pages whatever the level), its visibility
  // their area-weighted mean.
  std::vector<double> leaf_sum(std::size_t(o.size()), 0), vis_sum(leaf_sum), area_sum(leaf_sum);
  for (int id = o.size() - 1; id >= 0; --id) {
    const OctreeNode& n = o.node(id);
    const NodeProjection& p = proj[std::size_t(id)];
    const NodeStats& s = tree_.stats(tree_.id(id, tree_.time().leaf_of(t)));
    if (n.is_leaf()) {
      // Culled, transparent or uniform at this step (drawn flat or skipped at any level).
      const bool empty = p.culled || s.empty() || slopes.transparent(s.min, s.max) || s.min == s.max;
      // Clipped away by a probe: drawn nowhere, at no cost.
      const bool clipped = !clip.empty() && clip[std::size_t(id)] == ClipSide::removed;
      leaf_sum[std::size_t(id)] =
          clipped ? 0.0 : p.pixel_area * p.depth_voxels / spacing * (empty ? kEmptyCostShare : 1.0);
      area_sum[std::size_t(id)] = p.pixel_area;
      // A stopped node (adaptive octrees) sees as its leaf bricks do on average.
      double vis = 0;
      int count = 0;
      o.for_each_brick(id, [&](int b) {
        vis += leaf_vis[std::size_t(b)];
        ++count;
      });
      vis_sum[std::size_t(id)] = p.pixel_area * vis / std::max(count, 1);
    } else {
      for (int c : n.children)
        if (c >= 0) {
          leaf_sum[std::size_t(id)] += leaf_sum[std::size_t(c)];
          area_sum[std::size_t(id)] += area_sum[std::size_t(c)];
          vis_sum[std::size_t(id)] += vis_sum[std::size_t(c)];
        }
    }
    const auto f = o.lod_factor(id);
    cost_[std::size_t(id)] = leaf_sum[std::size_t(id)] / double(std::max({f[0], f[1], f[2]}));
    const double visibility =
        area_sum[std::size_t(id)] > 0 ? vis_sum[std::size_t(id)] / area_sum[std::size_t(id)] : 0;
    const std::array<double, 3> c = centre(geometric_box(n.box, d));
    // The centre of attention weighs by distance and field of view only when one is given: the
    // image's mean ΔE counts every pixel alike, and weighting by the volume centre raised it at
    // equal frame time (docs/results.md).
    const double attention =
        options_.focus ? focus_weight(c, focus, diagonal) * view_weight(p, camera) : 1.0;
    error_[std::size_t(id)] = !clip.empty() && clip[std::size_t(id)] == ClipSide::removed
                                  ? 0.0  // clipped away: no level shows anything of it
                                  : lod_error(tree_, id, t, p, slopes, attention * visibility);
  }
}

const char* to_string(LodFallback f) { return f == LodFallback::splats ? "splats" : "scale"; }

LodFallback parse_lod_fallback(const std::string& text, const std::string& option) {
  if (text == "scale") return LodFallback::scale;
  if (text == "splats") return LodFallback::splats;
  throw UsageError(option + " " + text + ": expected scale or splats");
}

void LodController::adapt_splats(ClipSides clip) {
  const double target = options_.target_ms;
  if (!splatting_) {
    // The coarsest textured cut was drawn and missed the target: splats from now on.
    if (!last_coarsest_ || !(last_ms_ > kScaleDownAt * target)) return;
    splatting_ = true;
    splat_ms_ = splat_area_ = 0;
    splat_budget_ = 0;
    splat_hold_ = 0;
  } else if (coarsest_cost_ > 0) {
    // Back to the textured cut once its coarsest cut, as measured last and scaled by its cost
    // in this view, fits well under the target.
    const double coarsest = coarsest_ms_ * cost_[0] / coarsest_cost_;
    if (coarsest < kScaleUpAt * target) {
      splatting_ = false;
      last_ms_ = coarsest;  // what the next (textured) frame is expected to take
      return;
    }
  }
  // The splat cut is refined largest splat first within a screen-area budget (TetSplat's
  // minimum splat size is what that budget amounts to), and the budget follows the last splat
  // frame: time in proportion to the splats' area; after a frame over the band it shrinks to
  // fit and holds a while. The cut grows by at most one split or a quarter of its nodes a
  // frame, so a prediction that is too low overshoots by little. The root alone until a splat
  // frame is measured.
  // Only a frame under the band may grow the cut; otherwise it keeps at most its nodes.
  int max_nodes = splat_.size;
  if (!(splat_ms_ > 0 && splat_area_ > 0)) {
    splat_budget_ = 0;
  } else if (splat_ms_ > (1 + kDeadBand) * target) {
    splat_budget_ = splat_area_ * target / splat_ms_;
    splat_hold_ = kSplatHoldFrames;
  } else if (splat_hold_ > 0) {
    --splat_hold_;
  } else if (splat_ms_ < (1 - kDeadBand) * target) {
    splat_budget_ = splat_area_ * target / splat_ms_;
    max_nodes = std::max(splat_.size + kChildrenPerSplit,
                         int(std::ceil(kMaxSplatGrowth * double(splat_.size))));
  }
  splat_ = splat_cut_within(tree_.octree(), proj_, splat_budget_, clip, max_nodes);
}

void LodController::adapt_scale(bool coarsest) {
  const double target = options_.target_ms;
  if (!(target > 0) || !(last_ms_ > 0)) {
    scale_ = 1;
    return;
  }
  // Pixels go as scale²: aim at the target with half a step (damped), in [kMinScale, 1].
  const double want = scale_of_last_ * std::sqrt(std::sqrt(target / last_ms_));
  if (coarsest && last_ms_ > kScaleDownAt * target)
    scale_ = std::clamp(want, kMinScale, 1.0);
  else if (scale_ < 1 && last_ms_ < kScaleUpAt * target)
    scale_ = std::clamp(want, kMinScale, 1.0);
}

namespace {

// One update's work on the cut: the split queue (largest error first), the merge queue
// (smallest first), the cut's running cost, and predictions anchored at the last measured frame
// — its cost then (its view and step) and its time — moving by the model's slope, so the
// intercept's lag and bias do not matter and a change of view or step (this frame's costs) is
// predicted: ms(c) = last_ms + b·(c − last_cost).
class CutPlanner {
 public:
  CutPlanner(LodCut& cut, const Octree& o, const std::vector<double>& cost,
             const std::vector<double>& error, const LodOptions& options,
             const CostModel& model, double last_ms, double last_cost)
      : cut_(cut), o_(o), node_cost_(cost), error_(error), options_(options), model_(model),
        last_ms_(last_ms), anchor_(last_cost), timed_(options.target_ms > 0),
        // Timed, the first frame (no measurement yet) keeps the coarsest cut.
        informed_(timed_ && model.ready() && last_ms > 0 && last_cost >= 0),
        target_(options.target_ms), low_((1 - kDeadBand) * target_),
        high_((1 + kDeadBand) * target_) {
    for (int id : cut_.nodes()) cost_ += node_cost_[std::size_t(id)];
    for (int id : cut_.nodes()) {
      if (cut_.can_split(id)) splits_.push({error_[std::size_t(id)], id});
      push_merge(o_.node(id).parent);
    }
  }

  // Over the band: merges the least useful parents first — but not below the band unless far
  // over (one merge near the root can halve the frame).
  void merge_over_band() {
    while (informed_ && predict(cost_) > high_ && !merges_.empty() &&
           merges_done_ < options_.merge_limit) {
      const auto [e, id] = merges_.top();
      merges_.pop();
      if (!cut_.can_merge(id)) continue;
      const double after = cost_ + node_cost_[std::size_t(id)] - children_cost(id);
      if (predict(after) < low_ && predict(cost_) < kFarOver * target_) break;
      do_merge(id);
    }
  }

  // Under budget: splits the most useful nodes, swapping one merge for a much better split.
  void split_under_budget() {
    const std::int64_t brick_bytes = brick_slot_bytes(o_);
    while (!splits_.empty() && splits_done_ < options_.split_limit) {
      const auto [e, id] = splits_.top();
      if (!cut_.can_split(id)) {
        splits_.pop();
        continue;
      }
      // Error 0 (uniform, transparent, hidden) never splits; below min_error only with time
      // left.
      if (!(e > 0) || (e <= options_.min_error && !(informed_ && predict(cost_) < low_))) break;
      const double after = cost_ - node_cost_[std::size_t(id)] + children_cost(id);
      const bool over_textures =
          options_.texture_budget > 0 &&
          std::int64_t(cut_.size() - 1 + children_count(id)) * brick_bytes >
              options_.texture_budget;
      if (!split_fits(after) || over_textures) {
        while (!merges_.empty() && !cut_.can_merge(merges_.top().second)) merges_.pop();
        if (merges_.empty() || merges_done_ >= options_.merge_limit ||
            merges_.top().first * kSwapGain > e)
          break;
        const int m = merges_.top().second;
        merges_.pop();
        if (o_.node(id).parent == m || m == id) break;  // never undo the split being paid for
        do_merge(m);
        continue;
      }
      splits_.pop();
      cost_ = after;
      cut_.split(id);
      ++splits_done_;
      for (int k : o_.node(id).children)
        if (k >= 0 && cut_.can_split(k)) splits_.push({error_[std::size_t(k)], k});
      push_merge(id);
    }
  }

  double cost() const { return cost_; }
  int splits_done() const { return splits_done_; }
  int merges_done() const { return merges_done_; }

 private:
  using Item = std::pair<double, int>;
  LodCut& cut_;
  const Octree& o_;
  const std::vector<double>& node_cost_;
  const std::vector<double>& error_;
  const LodOptions& options_;
  const CostModel& model_;
  double last_ms_, anchor_;
  bool timed_, informed_;
  double target_, low_, high_;
  double cost_ = 0;
  int splits_done_ = 0, merges_done_ = 0;
  std::priority_queue<Item> splits_;                                       // largest first
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> merges_;  // smallest first

  double predict(double c) const {
    const double anchored = last_ms_ + model_.slope() * (c - anchor_);
    return kAnchorShare * anchored + (1 - kAnchorShare) * model_.predict(c);
  }
  // A split fits when it stays under the target, or within the band's top when the cut is
  // below the band (the first split from a fast coarse cut may overshoot a little). After the
  // first of a frame, splits add at most kMaxGrowth of the drawn frame's cost: a refinement
  // takes a few frames, and a model that underestimates a big change cannot overshoot by much.
  bool split_fits(double after) const {
    if (!timed_) return true;
    if (!informed_) return false;
    if (splits_done_ > 0 && after > (1 + kMaxGrowth) * std::max(anchor_, cost_)) return false;
    return predict(after) <= target_ || (predict(cost_) < low_ && predict(after) <= high_);
  }
  double children_cost(int id) const {
    double c = 0;
    for (int k : o_.node(id).children)
      if (k >= 0) c += node_cost_[std::size_t(k)];
    return c;
  }
  int children_count(int id) const {
    int n = 0;
    for (int k : o_.node(id).children) n += k >= 0;
    return n;
  }
  void push_merge(int id) {
    if (id >= 0 && cut_.can_merge(id)) merges_.push({error_[std::size_t(id)], id});
  }
  void do_merge(int id) {
    cost_ += node_cost_[std::size_t(id)] - children_cost(id);
    cut_.merge(id);
    ++merges_done_;
    splits_.push({error_[std::size_t(id)], id});
    push_merge(o_.node(id).parent);
  }
};

}  // namespace

LodFrameStats LodController::update(const Camera& camera, int t, const TransferFunction& tf,
                                    double spacing, ClipSides clip) {
  const TfColourSlopes slopes(tf);
  evaluate(camera, t, tf, slopes, spacing, clip);
  CutPlanner plan(cut_, tree_.octree(), cost_, error_, options_, model_, last_ms_, last_cost_);
  plan.merge_over_band();
  // At the coarsest cut and still over: a smaller render target, or splats; no split until the
  // frame is back at full size and textured.
  if (options_.target_ms > 0 && options_.fallback == LodFallback::splats) {
    scale_ = 1;
    adapt_splats(clip);
  } else {
    splatting_ = false;
    adapt_scale(last_coarsest_);
  }
  if (scale_ >= 1 && !splatting_) plan.split_under_budget();
  const double cost = plan.cost();
  last_cost_ = cost;
  last_coarsest_ = cut_.size() == 1;
  LodFrameStats st = cut_stats(cut_);
  st.splits = plan.splits_done();
  st.merges = plan.merges_done();
  st.cost = cost;
  st.predicted_ms = model_.ready() ? model_.predict(cost) : 0;
  st.render_scale = scale_;
  scale_of_frame_ = scale_;
  if (splatting_) {
    st.splat_px = splat_.min_px;
    st.splats = splat_.size;
  }
  for (int id : cut_.nodes())
    if (cut_.can_split(id)) st.max_error = std::max(st.max_error, error_[std::size_t(id)]);
  return st;
}

LodFrameStats cut_stats(const LodCut& cut) {
  LodFrameStats st;
  st.cut_size = cut.size();
  st.nodes_per_level = cut.nodes_per_level();
  st.texture_bytes = cut.texture_bytes();
  return st;
}

std::vector<int> LodController::likely_split_bricks(int n) const {
  const Octree& o = tree_.octree();
  std::vector<std::pair<double, int>> candidates;
  for (int id : cut_.nodes())
    if (cut_.can_split(id) && error_[std::size_t(id)] > 0)
      candidates.push_back({error_[std::size_t(id)], id});
  std::sort(candidates.begin(), candidates.end(), std::greater<>());
  std::vector<int> bricks;
  for (std::size_t i = 0; i < candidates.size() && int(i) < n; ++i)
    for (int c : o.node(candidates[i].second).children)
      if (c >= 0) bricks.push_back(o.node_brick(c));
  return bricks;
}

void LodController::measured(double ms) {
  if (splatting_) {  // a splat frame: the splat cut's own measure, not the textured cut's
    splat_ms_ = ms;
    splat_area_ = splat_.pixel_area;
    return;
  }
  if (last_coarsest_ && scale_of_frame_ >= 1) {
    coarsest_ms_ = ms;
    coarsest_cost_ = last_cost_;
  }
  last_ms_ = ms;
  scale_of_last_ = scale_of_frame_;
  // The model is fitted on full-size frames only (a smaller target changes every pixel's cost).
  if (last_cost_ >= 0 && scale_of_frame_ >= 1) model_.add(last_cost_, ms);
}

void to_json(nlohmann::json& j, const LodFrameStats& s) {
  j = {{"cut_size", s.cut_size},         {"nodes_per_level", s.nodes_per_level},
       {"splits", s.splits},             {"merges", s.merges},
       {"texture_bytes", s.texture_bytes}, {"cost", s.cost},
       {"predicted_ms", s.predicted_ms}, {"max_error", s.max_error},
       {"render_scale", s.render_scale}, {"splat_px", s.splat_px},
       {"splats", s.splats}};
}

}  // namespace tsp
