// Parsing of option values shared by the subcommands; every failure is a tsp::UsageError that
// names the option, the text given and what was expected.
#pragma once
#include <array>
#include <string>
#include <utility>

#include "tsp/core/types.h"

namespace tspcli {

/// Whole-string decimal integer in [lo, hi]; throws UsageError("OPTION 'TEXT': expected EXPECTED").
long long parse_integer(const std::string& text, const std::string& option, long long lo,
                        long long hi, const std::string& expected);

/// Whole-string floating-point number; throws UsageError naming the option.
double parse_number(const std::string& text, const std::string& option);

/// "X,Y,Z": three whole-string numbers (`expected` says what they are); throws UsageError
/// quoting the whole text.
std::array<double, 3> parse_triple(const std::string& text, const std::string& option,
                                   const std::string& expected);

/// "X,Y,Z" (or "N" for a cube when allow_cube) with every edge in [1, max_edge]; throws UsageError.
tsp::Dims parse_dims(const std::string& text, const std::string& option, int max_edge,
                     bool allow_cube);

/// "LO:HI" in data units (a leading '-' is a sign); throws UsageError. LO < HI is checked later.
tsp::ValueRange parse_range(const std::string& text, const std::string& option);

/// Steps first..last (inclusive; last −1: the last step), every stride-th.
struct StepRange {
  int first = 0, last = -1, stride = 1;
};

/// --steps "A:B", "A:", "A" or "A:B:S" (every S-th step from A to B, S ≥ 1). Throws UsageError
/// quoting the whole text.
StepRange parse_steps(const std::string& text);

/// --size "WxH" with both in [1, 8192]; throws UsageError.
std::pair<int, int> parse_size(const std::string& text);

}  // namespace tspcli
