#include "render/render_settings.h"

#include <cmath>

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
  if (!(s.spacing >= kMinSliceSpacing && s.spacing <= kMaxSliceSpacing))
    throw tsp::UsageError("--spacing " + number_text(s.spacing) +
                          ": expected a slice spacing in [" + number_text(kMinSliceSpacing) + ", " +
                          number_text(kMaxSliceSpacing) + "] voxels");
  for (auto [name, v] : {std::pair{"--spatial-tol", s.tol.spatial},
                         std::pair{"--temporal-tol", s.tol.temporal}})
    if (!(v >= 0) || !std::isfinite(v))
      throw tsp::UsageError(std::string(name) + " " + number_text(v) +
                            ": expected a finite tolerance >= 0");
  if (!(s.sampling_tol >= 0) || !std::isfinite(s.sampling_tol))
    throw tsp::UsageError("--sampling-tol " + number_text(s.sampling_tol) +
                          ": expected a finite colour change per step >= 0");
  if (const std::string why = sampling_conflict(s); !why.empty()) throw tsp::UsageError(why);
  if (!(s.refine_tol >= 0) || !std::isfinite(s.refine_tol))
    throw tsp::UsageError("--refine-tol " + number_text(s.refine_tol) +
                          ": expected a finite TF variation >= 0");
  if (!(s.render_scale >= kMinRenderScale && s.render_scale <= 1))
    throw tsp::UsageError("render scale " + number_text(s.render_scale) +
                          ": expected a share in [" + number_text(kMinRenderScale) + ", 1]");
  if (s.upload_budget < 0 || s.upload_budget > kMaxBudgetBytes)
    throw tsp::UsageError("upload budget " + std::to_string(s.upload_budget) +
                          " bytes: expected 0 (no limit) to " + std::to_string(kMaxBudgetBytes));
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
