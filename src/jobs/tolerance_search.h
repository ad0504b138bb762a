// Table 4's search (docs/bench.md): for each target mean ΔE, the largest tolerance (spatial =
// temporal) whose pictures stay within it, found by bisection on a log scale between the
// smallest positive and the largest node error. Pure logic over an error-evaluation callback,
// so it is tested without GL.
#pragma once
#include <functional>
#include <vector>

#include "tsp/metric/metric.h"

namespace tspgl {

/// The search's low bracket is at most this many decades below the largest node error.
inline constexpr double kMaxSearchDecades = 9;

/// Smallest positive and largest finite e_s or e_t of a non-transparent node: below the first
/// every traversal is the zero-tolerance one; at or above the second it stops at the root.
struct ErrorSpan {
  double smallest_positive = 0, largest = 0;
};

/// The ErrorSpan of m (both 0 when no node has a positive finite error). Never throws.
ErrorSpan error_span(const tsp::MetricResult& m);

/// One target's result.
struct FoundTolerance {
  double target = 0;   ///< target mean ΔE
  double tol = 0;      ///< the tolerance found (0: only zero tolerance meets it, or nothing does)
  double mean_de = 0;  ///< mean ΔE at tol
  bool met = false;    ///< mean_de ≤ target
};

/// Mean ΔE of the pictures at a tolerance (may throw; the search passes it on).
using ErrorAt = std::function<double(double tolerance)>;

/// For each target (> 0): the largest tolerance in {0} ∪ [lo, span.largest] reached by
/// `iterations` bisection steps on log(tol), lo = max(span.smallest_positive,
/// span.largest·10^−kMaxSearchDecades), keeping the invariant that lo meets the target and hi
/// does not; span.largest itself when it meets the target. error_at is called at most once per
/// distinct tolerance (results are shared between targets), first at 0. Throws what error_at
/// throws.
std::vector<FoundTolerance> search_tolerances(const ErrorAt& error_at, const ErrorSpan& span,
                                              const std::vector<double>& targets, int iterations);

/// The steps a tolerance search renders: all of first..last when there are at most `count`,
/// else `count` steps spread evenly with both ends included. Never throws.
std::vector<int> search_step_sample(int first, int last, int count);

}  // namespace tspgl
