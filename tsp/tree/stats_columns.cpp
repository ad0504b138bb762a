#include "tsp/tree/stats_columns.h"

#include <cassert>
#include <tuple>
#include <utility>

namespace tsp {

namespace {

// Each NodeStats field beside the column that holds it: the one list both directions walk.
constexpr std::tuple kFields{std::pair{&NodeStats::mean, &StatsColumns::mean},
                             std::pair{&NodeStats::std, &StatsColumns::std},
                             std::pair{&NodeStats::min, &StatsColumns::min},
                             std::pair{&NodeStats::max, &StatsColumns::max},
                             std::pair{&NodeStats::spatial_error, &StatsColumns::spatial_error},
                             std::pair{&NodeStats::temporal_error, &StatsColumns::temporal_error}};

// Calls f(field, column) with the member pointers of every pair in kFields.
template <class F>
void for_each_field(F&& f) {
  std::apply([&](const auto&... p) { (f(p.first, p.second), ...); }, kFields);
}

}  // namespace

StatsColumns stats_columns(const TspTree& tree) {
  StatsColumns c;
  for_each_field([&](auto field, auto column) {
    auto& col = c.*column;
    col.resize(std::size_t(tree.size()));
    for (int i = 0; i < tree.size(); ++i) col[std::size_t(i)] = tree.stats(i).*field;
  });
  return c;
}

void set_stats(TspTree& tree, const StatsColumns& c) {
  for_each_field([&](auto field, auto column) {
    const auto& col = c.*column;
    assert(col.size() == std::size_t(tree.size()));
    for (int i = 0; i < tree.size(); ++i) tree.stats(i).*field = col[std::size_t(i)];
  });
}

}  // namespace tsp
