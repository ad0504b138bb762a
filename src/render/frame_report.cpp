#include "render/frame_report.h"

#include <nlohmann/json.hpp>

namespace tspgl {

void to_json(nlohmann::json& j, const FrameReport& r) {
  j = {{"step", r.step},
       {"ms", r.ms},
       {"traversal_ms", r.traversal_ms},
       {"slicing_ms", r.slicing_ms},
       {"upload_ms", r.upload_ms},
       {"draw_ms", r.draw_ms},
       {"bytes_uploaded", r.bytes_uploaded},
       {"bytes_stitched", r.bytes_stitched},
       {"textures_resident", r.textures_resident},
       {"texture_bytes", r.texture_bytes},
       {"deferred_textures", r.deferred_textures},
       {"polygons", r.polygons},
       {"boxes", r.boxes},
       {"fragments", r.fragments},
       {"redrawn_percent", r.redrawn_percent},
       {"dense", r.dense},
       {"caster", r.backend},
       {"samples", r.samples},
       {"step_multiplier", r.step_multiplier},
       {"steps_merged", {r.spans_lo, r.spans_hi}},
       {"steps_shown", {r.shown_lo, r.shown_hi}}};
  add_class_shares(j, r.class_percent);
  if (!r.backend_note.empty()) j["caster_note"] = r.backend_note;
}

void add_class_shares(nlohmann::json& j, std::span<const double> shares) {
  for (std::size_t c = 0; c < shares.size() && c < std::size_t(tsp::kDrawClassCount); ++c)
    j[tsp::to_string(tsp::DrawClass(c))] = shares[c];
}

}  // namespace tspgl
