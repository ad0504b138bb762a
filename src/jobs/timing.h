// A timed render run summarised over its last pass: what `bench`'s report.json and the demo's
// report.json record of a run, with one JSON form (to_json) for both.
#pragma once
#include <array>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "jobs/render_job.h"

namespace tspgl {

/// A timed render run summarised over its last pass.
struct Timing {
  double median_ms = 0, first_pass_median_ms = 0, metric_ms = 0;
  std::vector<int> steps;
  std::vector<double> step_ms;  ///< last pass, per step
  std::array<double, 4> classes{};  ///< mean class shares (NR, UP, RT, NT), percent
  double bytes_uploaded = 0;        ///< mean per frame, last pass
  std::string renderer;             ///< the GL renderer string
};

/// The Timing of a render job's result over pass `last_pass` (the first pass's median beside
/// it). Never throws but std::bad_alloc.
Timing timing_of(const RenderJobResult& r, int last_pass);

/// Timing as JSON: median_ms, first_pass_median_ms, metric_ms, steps, step_ms,
/// bytes_uploaded_per_frame and the Table-5 classes by name (frames.json's class keys); the
/// renderer string is the caller's (report.json's top level). Never throws but std::bad_alloc.
void to_json(nlohmann::json& j, const Timing& t);

}  // namespace tspgl
