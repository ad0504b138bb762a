// The one way text becomes JSON: nlohmann's parser with a nesting limit (a file nested 100,000
// deep crashed every reader on the way back out) and error messages that quote at most a short
// excerpt of the input.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace tsp {

/// Deepest nesting of arrays and objects a JSON input may have (ours need 4).
inline constexpr int kMaxJsonDepth = 64;
/// Longest parser message quoted in an error (nlohmann's quote what they read last).
inline constexpr std::size_t kMaxJsonMessage = 160;

/// Parses text as JSON. Throws tsp::FormatError "ORIGIN: not valid JSON: ..." (the parser's
/// message cut to kMaxJsonMessage characters) on a syntax error, a number beyond the double
/// range, or nesting deeper than kMaxJsonDepth.
nlohmann::json parse_json(std::string_view text, const std::string& origin);

}  // namespace tsp
