#include "jobs/timing.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "render/frame_report.h"

namespace tspgl {

Timing timing_of(const RenderJobResult& r, int last_pass) {
  Timing t;
  t.median_ms = median_frame_ms(r, last_pass);
  t.first_pass_median_ms = median_frame_ms(r, 1);
  t.metric_ms = r.metric_ms;
  t.renderer = r.renderer;
  for (const FrameRecord& f : r.frames) {
    if (f.pass != last_pass) continue;
    t.steps.push_back(f.report.step);
    t.step_ms.push_back(f.report.ms);
    for (std::size_t c = 0; c < 4; ++c) t.classes[c] += f.report.class_percent[c];
    t.bytes_uploaded += double(f.report.bytes_uploaded);
  }
  const double n = double(std::max<std::size_t>(1, t.steps.size()));
  for (double& c : t.classes) c /= n;
  t.bytes_uploaded /= n;
  return t;
}

void to_json(nlohmann::json& j, const Timing& t) {
  j = {{"median_ms", t.median_ms}, {"first_pass_median_ms", t.first_pass_median_ms},
       {"metric_ms", t.metric_ms}, {"steps", t.steps},
       {"step_ms", t.step_ms},     {"bytes_uploaded_per_frame", t.bytes_uploaded}};
  add_class_shares(j, t.classes);
}

}  // namespace tspgl
