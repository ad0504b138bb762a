// The frame-time model of the LOD controller (issue "LOD cut" item 4): a frame costs
// a + b·Σ cost(node) over the cut, cost = pixels covered × samples along the view. Both are
// fitted online to the measured frame times: the slope b by least squares over a long window
// (exponential forgetting) whenever the costs seen spread enough to identify it, the intercept a
// over a short window given b — so a view change (which moves the fixed per-pixel cost) is
// followed within a few frames. Until b is identified, half of the recent frames' time is taken
// as fixed cost.
#pragma once

namespace tsp {

/// Online fit of ms = a + b·cost. Not thread-safe.
class CostModel {
 public:
  /// Forgetting factors per frame for the slope's and the intercept's windows, in (0, 1].
  explicit CostModel(double slope_forgetting = 0.95, double intercept_forgetting = 0.6);
  /// Adds one measured frame (cost ≥ 0, ms > 0, both finite; others are ignored).
  void add(double cost, double ms);
  /// True once a frame has been added.
  bool ready() const { return slope_ > 0; }
  /// Predicted milliseconds for a cut of this cost (0 before the first frame).
  double predict(double cost) const { return ready() ? intercept_ + slope_ * cost : 0; }
  /// Fitted intercept a (ms).
  double intercept() const { return intercept_; }
  /// Fitted slope b (ms per cost unit; 0 before the first frame).
  double slope() const { return slope_; }

 private:
  struct Sums {
    double w = 0, x = 0, y = 0, xx = 0, xy = 0;
    void add(double lambda, double x, double y);
  };
  double slope_lambda_, intercept_lambda_;
  Sums long_, short_;
  double slope_ = 0, intercept_ = 0;
  bool identified_ = false;
};

}  // namespace tsp
