// A player session (issue 47 item 4): what the window restores when the same input is played
// again — the transfer function (editor edits included), camera, step, playback speed, probes,
// surface, axis scale and panel layout — as a small versioned JSON file. One per input and field
// beside the other caches (DIR/sessions/session-HASH.json, written when the window quits or opens
// another input), or anywhere as a shared file (File > Save session..., play --session FILE).
// A value type and its files: no window, no GL. Format: docs/player.md#sessions.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tsp/frame/camera.h"
#include "tsp/metric/transfer_function.h"

namespace tspplayer {

/// Version of the session file; a file of another version is never read (nor overwritten until
/// the window saves its session).
inline constexpr int kSessionVersion = 1;
/// Largest session file read (a real one is a few tens of KiB: the TF's entries).
inline constexpr std::int64_t kMaxSessionBytes = std::int64_t(4) << 20;

/// What a session holds. Every member has the player's default, so a partial state is whole.
struct Session {
  std::string input;  ///< the input as the user named it (absolute), for people reading the file
  std::string field;  ///< the field shown ("": the file's first)
  // The transfer function: its table as the window last drew it, the editor's handles, and the
  // name the preset combo showed ("edited" after an edit).
  tsp::ValueRange tf_domain{0, 1};
  std::vector<tsp::Rgba> tf_entries;  ///< empty: no TF kept (the player's start TF)
  std::vector<tsp::TfPoint> tf_points;
  std::string tf_label = "auto";
  bool log_opacity = false;
  // The view: the orbit camera's angles, zoom, pan, projection, field of view and any free eye
  // (the frame and voxel size follow from the file and the axis scale).
  double azimuth_deg = 30, elevation_deg = 20, zoom = 1, fov_deg = 30;
  bool perspective = false;
  std::array<double, 2> pan{0, 0};
  std::optional<std::array<double, 3>> eye;
  std::array<double, 3> scale{1, 1, 1};  ///< the axis stretch (--scale)
  int step = 0;
  double speed = 0;  ///< steps per second (0: the series' default speed)
  bool loop = true, every_step = true;
  std::vector<std::string> probes;  ///< as --probe takes them
  std::string probe_op = "intersect";
  bool probe_surface = true;
  bool surface = false;  ///< the mesh's boundary drawn (--surface boundary)
  // The panels: shown (Tab), the annotations over the volume, and Dear ImGui's own state — its
  // settings text (floating windows' places and sizes) and, per window, which sections are open.
  bool panels = true, annotations = true;
  std::string ui_ini;
  nlohmann::json ui_open = nlohmann::json::object();  ///< window name → [[id, 0|1], ...]
  bool operator==(const Session&) const;
};

/// The session as JSON: {"version": kSessionVersion, "input", "field", "tf": {...}, "camera":
/// {...}, ...}. Never throws but bad_alloc.
nlohmann::json to_json(const Session& s);
/// Reads a session's JSON; origin names it in messages. Throws tsp::FormatError naming origin
/// and what is wrong (not an object, another version, a value of the wrong type or range).
Session session_from_json(const nlohmann::json& j, const std::string& origin);

/// Reads the session file at path (a regular file of at most kMaxSessionBytes, through the input
/// gate). Throws tsp::IoError (missing, unreadable, not a regular file) or tsp::FormatError
/// naming path.
Session read_session(const std::string& path);
/// Writes s to path atomically. A cache entry's folder is made, and a link planted at its name is
/// replaced, not followed (tsp::OutputLinks::replace); a path the user named follows links.
/// Throws tsp::IoError naming the path.
void write_session(const std::string& path, const Session& s, bool cache_entry);

/// The session file of input (as the user named it; made absolute) and field under the cache
/// folder dir ("": default_calibration_dir()): DIR/sessions/session-HASH.json; "" when there is
/// no cache folder or dir is "-". Never throws but bad_alloc.
std::string session_cache_path(const std::string& input, const std::string& field,
                               const std::string& dir = "");

}  // namespace tspplayer
