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
       {"not_rendered", r.class_percent[0]},
       {"untextured", r.class_percent[1]},
       {"reused_texture", r.class_percent[2]},
       {"new_texture", r.class_percent[3]},
       {"clipped", r.class_percent[4]},
       {"bytes_uploaded", r.bytes_uploaded},
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
  if (!r.backend_note.empty()) j["caster_note"] = r.backend_note;
}

}  // namespace tspgl
