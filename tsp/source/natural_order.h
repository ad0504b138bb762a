// Numeric-aware ordering of names ("step2" before "step10"), shared by every reader that
// turns a set of names (HDF5 group members, globbed files) into a time order.
#pragma once
#include <string>
#include <vector>

namespace tsp::io {

/// True when a sorts before b: runs of digits compare by value (then by length, so "07"
/// follows "7"), other characters compare bytewise. Never throws.
bool natural_less(const std::string& a, const std::string& b);

/// Sorts names in place by natural_less. Never throws.
void natural_sort(std::vector<std::string>& names);

}  // namespace tsp::io
