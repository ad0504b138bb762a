// The one way JSON becomes text: invalid UTF-8 in strings (a Latin-1 file name, a non-UTF-8
// attribute of an input file) is replaced by U+FFFD instead of throwing, so a report is never
// lost to a name it quotes.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace tsp {

/// j as text (indent < 0: one line), invalid UTF-8 replaced by U+FFFD. Never throws on strings.
inline std::string json_text(const nlohmann::json& j, int indent = -1) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace tsp
