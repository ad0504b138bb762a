// What a frame reports (timings, counts, Table-5 classes): shared by the TSP renderer, the
// non-TSP baseline, the render and bench jobs and the player. What it is drawn with is
// render_settings.h.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "render/render_settings.h"
#include "tsp/frame/frame_plan.h"
#include "tsp/tree/traversal.h"

namespace tspgl {

/// Timings and counts of one frame (the frames.json record, less pass).
struct FrameReport {
  int step = 0;
  /// The steps the drawn nodes stand for (the union of their time spans): wider than [step,
  /// step] when a temporal tolerance merged steps.
  int spans_lo = 0, spans_hi = 0;
  /// The steps whose bricks textured them (every step of a span textured by its mean).
  int shown_lo = 0, shown_hi = 0;
  /// Some texture holds a span's mean (--span-step mean) rather than one step.
  bool shows_mean = false;
  double ms = 0;            ///< whole frame, glFinish included
  double traversal_ms = 0;  ///< traversal and frame plan
  double slicing_ms = 0;    ///< slice polygons and their vertex buffer
  double upload_ms = 0;     ///< brick reads and texture uploads
  double draw_ms = 0;       ///< draw calls and glFinish
  /// Adaptive sampling: the mean step multiplier over the frame's full-resolution textured
  /// bricks (1: every spacing).
  double step_multiplier = 1;
  std::array<double, tsp::kDrawClassCount> class_percent{};  ///< NR, UP, RT, NT, clipped by voxels
  std::int64_t bytes_uploaded = 0;
  /// Slots rewritten so that neighbouring bricks drawn from other steps share their faces
  /// (BrickTextures::stitch), in bytes; not in bytes_uploaded.
  std::int64_t bytes_stitched = 0;
  std::int64_t textures_resident = 0;
  std::int64_t texture_bytes = 0;
  std::int64_t polygons = 0;           ///< slice polygons drawn
  std::int64_t boxes = 0;              ///< boxes drawn whole (ray cast or exact flat)
  std::int64_t fragments = 0;          ///< fragments drawn, not discarded (GL_SAMPLES_PASSED)
  double redrawn_percent = 100;        ///< share of the image drawn again (partial-image reuse)
  /// Who cast the rays: "gl" or "cpu" (render/cpu_caster.h).
  std::string backend = "gl";
  /// Why a frame asked to be cast on the CPU was drawn by GL (empty: it was not).
  std::string backend_note;
  /// CPU frames: the samples the caster read through a TF (0 for GL frames).
  std::int64_t samples = 0;
  bool dense = false;  ///< ray cast as one whole-volume texture (DenseVolume), not the brick grid
  std::int64_t deferred_textures = 0;  ///< textures left for later frames (upload_budget)
  /// A partial frame (PartialFrame) drawn with other inputs than the earlier parts of its
  /// picture: those parts must be drawn again.
  bool partial_stale = false;
  /// True when every texture the frame needs was drawn (nothing deferred).
  bool complete() const { return deferred_textures == 0; }
};

/// FrameReport as JSON: frames.json's keys for a frame (ms, the *_ms phases, the five Table-5
/// classes by name, caster and caster_note, samples, steps_merged, steps_shown, …), used by
/// frames.json, the player's stats and the bench's report alike. Never throws but bad_alloc.
void to_json(nlohmann::json& j, const FrameReport& r);

/// Adds the Table-5 classes' shares (percent, in DrawClass order: the first shares.size() of
/// them) to the object j, each keyed by tsp::to_string(DrawClass) ("not_rendered", …): the one
/// writer of those keys for frames.json, the bench's report and the player's stats.
void add_class_shares(nlohmann::json& j, std::span<const double> shares);

}  // namespace tspgl
