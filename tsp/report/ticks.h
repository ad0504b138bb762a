// Round tick values for an axis or a colour legend: multiples of 1, 2 or 5 × 10^k inside a
// range, so a legend reads 0.2 0.4 0.6 rather than 0.1998 0.3999 0.5999.
#pragma once
#include <string>
#include <vector>

namespace tsp {

/// The values k·step in [lo, hi] (inclusive, up to a rounding of step·1e-9), step the
/// smallest 1, 2 or 5 × 10^k giving at most max_ticks of them (≥ 2); at least the two ends
/// when no such step exists (lo == hi, NaN). Increasing. Never throws but bad_alloc.
std::vector<double> nice_ticks(double lo, double hi, int max_ticks);

/// A tick value as text: %g of v (0 for |v| below 1e-12 of the step, so no "-1.2e-17"). Never
/// throws but bad_alloc.
std::string tick_text(double v, double step);

}  // namespace tsp
