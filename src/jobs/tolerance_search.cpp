#include "jobs/tolerance_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace tspgl {

ErrorSpan error_span(const tsp::MetricResult& m) {
  ErrorSpan s;
  s.smallest_positive = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < m.errors.spatial.size(); ++i) {
    if (m.transparent[i]) continue;
    for (float e : {m.errors.spatial[i], m.errors.temporal[i]}) {
      if (!std::isfinite(e)) continue;
      s.largest = std::max(s.largest, double(e));
      if (e > 0) s.smallest_positive = std::min(s.smallest_positive, double(e));
    }
  }
  if (!std::isfinite(s.smallest_positive)) s.smallest_positive = 0;
  return s;
}

std::vector<FoundTolerance> search_tolerances(const ErrorAt& error_at, const ErrorSpan& span,
                                              const std::vector<double>& targets, int iterations) {
  std::map<double, double> known;
  auto eval = [&](double tol) {
    auto it = known.find(tol);
    if (it != known.end()) return it->second;
    const double de = error_at(tol);
    known[tol] = de;
    return de;
  };
  const double zero_de = eval(0);
  const double top = span.largest;
  std::vector<FoundTolerance> out;
  for (double target : targets) {
    FoundTolerance f;
    f.target = target;
    if (top <= 0) {
      f.tol = 0;
    } else if (eval(top) <= target) {
      f.tol = top;  // even the coarsest picture is within the target
    } else {
      double lo = std::max(span.smallest_positive, top * std::pow(10.0, -kMaxSearchDecades));
      double hi = top;
      if (eval(lo) > target) {
        f.tol = 0;
      } else {
        // Invariant: lo meets the target, hi does not.
        for (int i = 0; i < iterations; ++i) {
          const double mid = std::sqrt(lo * hi);
          (eval(mid) <= target ? lo : hi) = mid;
        }
        f.tol = lo;
      }
    }
    f.mean_de = f.tol == 0 ? zero_de : eval(f.tol);
    f.met = f.mean_de <= target;
    out.push_back(f);
  }
  return out;
}

std::vector<int> search_step_sample(int first, int last, int count) {
  std::vector<int> out;
  const int n = last - first + 1;
  if (count <= 0 || n <= 0) return out;
  if (n <= count) {
    for (int t = first; t <= last; ++t) out.push_back(t);
  } else if (count == 1) {
    out.push_back(first);
  } else {
    for (int i = 0; i < count; ++i)
      out.push_back(first + int(std::lround(double(i) * (n - 1) / (count - 1))));
  }
  return out;
}

}  // namespace tspgl
