#include "tsp/core/json_read.h"

#include "tsp/core/error.h"

namespace tsp {

namespace {

// Thrown from the parser callback when the nesting gets too deep (caught below).
struct TooDeep {};

std::string excerpt(const std::string& message) {
  return message.size() <= kMaxJsonMessage ? message
                                           : message.substr(0, kMaxJsonMessage) + "...";
}

}  // namespace

nlohmann::json parse_json(std::string_view text, const std::string& origin) {
  using nlohmann::json;
  const json::parser_callback_t limit = [](int depth, json::parse_event_t event, json&) {
    if ((event == json::parse_event_t::object_start ||
         event == json::parse_event_t::array_start) &&
        depth >= kMaxJsonDepth)
      throw TooDeep{};
    return true;
  };
  try {
    return json::parse(text.begin(), text.end(), limit);
  } catch (const TooDeep&) {
    throw FormatError(origin + ": not valid JSON: arrays and objects nested deeper than " +
                      std::to_string(kMaxJsonDepth) + " levels");
  } catch (const json::exception& e) {  // syntax, and numbers beyond the double range
    throw FormatError(origin + ": not valid JSON: " + excerpt(e.what()));
  }
}

}  // namespace tsp
