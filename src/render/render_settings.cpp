#include "render/render_settings.h"

#include "render/settings_table.h"
#include "tsp/core/error.h"
#include "tsp/core/number_text.h"

namespace tspgl {

using tsp::number_text;

const char* to_string(Compositing c) {
  return c == Compositing::rays ? "rays" : c == Compositing::boxes ? "boxes" : "slices";
}

const char* to_string(Backend b) {
  return b == Backend::cpu ? "cpu" : b == Backend::gl ? "gl" : "auto";
}

Compositing parse_compositing(const std::string& text, const std::string& option) {
  if (text == "rays") return Compositing::rays;
  if (text == "slices") return Compositing::slices;
  if (text == "boxes") return Compositing::boxes;
  throw tsp::UsageError(option + " " + text + ": expected slices, boxes or rays");
}

void validate(const RenderSettings& s) {
  for (const SettingSpec& spec : settings_table())  // the table's ranges and messages
    check_setting(s, spec, "--" + std::string(spec.name));
  if (const std::string why = sampling_conflict(s); !why.empty()) throw tsp::UsageError(why);
}

SamplingMode resolve_sampling(const RenderSettings& s) {
  if (s.sampling_tol > 0) return SamplingMode::adaptive;
  if (s.preintegrated) return SamplingMode::preintegrated;
  return s.refine_tol > 0 ? SamplingMode::refined : SamplingMode::segments;
}

std::string sampling_conflict(const RenderSettings& s) {
  if (!(s.sampling_tol > 0 && s.preintegrated)) return "";
  return "--sampling-tol " + number_text(s.sampling_tol) +
         " with --preintegrated on: adaptive sampling uses the point lookup; choose one";
}

std::string settle_sampling(RenderSettings& s, const std::string& changed) {
  if (sampling_conflict(s).empty()) return "";
  if (changed == "preintegrated") {
    s.sampling_tol = 0;
    return "adaptive sampling turned off: pre-integration is on (the two exclude each other)";
  }
  s.preintegrated = false;
  return "pre-integration turned off: adaptive sampling is on (the two exclude each other)";
}

void validate_budget(std::int64_t bytes, const std::string& what) {
  if (bytes < 1 || bytes > kMaxBudgetBytes)
    throw tsp::UsageError(what + " " + std::to_string(bytes) + " bytes: expected 1 to " +
                          std::to_string(kMaxBudgetBytes) + " bytes (1 TiB)");
}

}  // namespace tspgl
