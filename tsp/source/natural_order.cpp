#include "tsp/source/natural_order.h"

#include <algorithm>
#include <cctype>

namespace tsp::io {
namespace {

bool is_digit(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) != 0;
}

// Compares the digit runs a[i..i_end) and b[j..j_end) by numeric value without converting
// (runs may be longer than any integer type): strip leading zeros, then longer is larger,
// then lexicographic. Returns <0, 0, >0.
int compare_digit_runs(const std::string& a, std::size_t i, std::size_t i_end, const std::string& b,
                       std::size_t j, std::size_t j_end) {
  while (i < i_end && a[i] == '0') ++i;
  while (j < j_end && b[j] == '0') ++j;
  std::size_t la = i_end - i, lb = j_end - j;
  if (la != lb) return la < lb ? -1 : 1;
  for (; i < i_end; ++i, ++j)
    if (a[i] != b[j]) return a[i] < b[j] ? -1 : 1;
  return 0;
}

}  // namespace

bool natural_less(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (is_digit(a[i]) && is_digit(b[j])) {
      std::size_t i_end = i, j_end = j;
      while (i_end < a.size() && is_digit(a[i_end])) ++i_end;
      while (j_end < b.size() && is_digit(b[j_end])) ++j_end;
      int c = compare_digit_runs(a, i, i_end, b, j, j_end);
      if (c != 0) return c < 0;
      // Equal values: fewer leading zeros first, so the order is total and deterministic.
      if (i_end - i != j_end - j) return i_end - i < j_end - j;
      i = i_end;
      j = j_end;
      continue;
    }
    if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
    ++i;
    ++j;
  }
  return a.size() - i < b.size() - j;
}

void natural_sort(std::vector<std::string>& names) {
  std::sort(names.begin(), names.end(), natural_less);
}

}  // namespace tsp::io
