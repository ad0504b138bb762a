// src/player: the window player and its action script; may include tsp/, gl/, render/.
// `tspplay play`: the window player (GLFW + Dear ImGui) over one .tsp file. Controls, script
// format and behaviour: docs/player.md.
#pragma once
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "jobs/play_input.h"
#include "render/render_settings.h"

namespace tspplayer {

/// Default quality target while playing: mean ΔE 1 against the full-quality picture.
inline constexpr double kDefaultPlayingQuality = 1;

/// Texture MiB a frame of the player uploads by default: render uploads all a frame needs, the
/// player spreads a large upload over frames so the window never stalls.
inline constexpr double kDefaultPlayerUploadMib = 16;

/// The settings the player starts with: render's defaults but kDefaultPlayerUploadMib.
tspgl::RenderSettings default_player_settings();

/// The playback speed a series of `steps` steps gets unless one is chosen: the whole series in
/// about kDefaultLoopSeconds, at most kDefaultMaxSpeed steps a second (a movie's rate) and at
/// least kMinSpeed — a 6-step series does not loop six times a second. Never throws.
double default_speed(int steps);
/// Seconds one pass over a short series takes at the default speed.
inline constexpr double kDefaultLoopSeconds = 4;
/// The default speed's ceiling, steps per second.
inline constexpr double kDefaultMaxSpeed = 24;

/// Everything `tspplay play` takes.
struct PlayerOptions {
  std::string tsp_path;              ///< the .tsp file
  std::string input_path;            ///< the input as given (an .h5 built into tsp_path; "": tsp_path)
  std::string field;                 ///< --field: the field shown first ("": the file's first)
  std::string cache_dir;             ///< --cache-dir: where File > Open builds inputs ("": default)
  tspgl::PlayInputOptions input;     ///< how File > Open reads and builds inputs: play's input options
  /// File > Open's "build options" line (`--raw-dims 64,64,64 --raw-type f32`, `--resolution
  /// 128`, `--xyz grid.xyz`, …) parsed as `play` parses them, on top of `input`: the same names,
  /// checks and errors (tsp::UsageError). Empty: the dialog takes no options.
  std::function<tspgl::PlayInputOptions(const std::string& line)> parse_input_options;
  std::string tf = "preset:auto";  ///< --tf: a file or preset:NAME
  std::string tf_range;              ///< --tf-range: auto (default), data, file or LO:HI
  int step = 0;                      ///< --step: the step shown first
  std::string screenshot;         ///< --screenshot: save the first complete frame here, then exit
  std::string script;             ///< --script: action script (run before --screenshot)
  int width = 960, height = 720;  ///< --size: window size in pixels
  /// The render settings table's options (--spacing, --compositing, --upload-budget, ...).
  tspgl::RenderSettings settings = default_player_settings();
  double ram_budget_mb = 1024;    ///< --ram-budget: bricks held in RAM, MiB
  double texture_budget_mb = 512; ///< --texture-budget: textures resident, MiB
  bool lod = true;                ///< --lod on|off: the adaptive LOD cut
  double target_fps = 30;         ///< --target-fps: held while interacting, in [1, 240]
  double speed = 0;               ///< --speed: playback, steps per second (0: default_speed)
  /// --quality: mean ΔE target while playing (0: none, the LOD cut holds the rate), tuned when
  /// playing starts.
  double quality = kDefaultPlayingQuality;
  bool keep_quality = true;       ///< --playback quality|rate: what gives while playing
  bool splat_fallback = false;    ///< --lod-fallback splats: splats when even the coarsest cut is slow
  std::string lod_filter = "error";  ///< --lod-filter error|distance[:K]|fov[:K]
  bool trace = false;             ///< --trace: one stdout line per applied change
  double frame_delay_ms = 0;      ///< --frame-delay-ms: a slow machine, for tests (0..2000)
  bool physical_proportions = true;      ///< --proportions physical|samples
  std::vector<std::string> probes;       ///< --probe: clip probes (as render --probe)
  std::string probe_op = "intersect";    ///< --probe-op
  bool probe_surface = true;             ///< --probe-surface on|off
  std::array<double, 3> scale{1, 1, 1};  ///< --scale: stretch per axis (exaggeration)
  /// --surface-mesh: the mesh series whose boundary settings.surface draws under the volume of
  /// the file opened first (play INPUT with --surface boundary: INPUT itself); "": none.
  std::string surface_mesh;
  std::string surface_field;  ///< --surface-field: the field it shows ("": the file's)
  std::string surface_tf;     ///< --surface-tf: its colours ("": cool-to-warm over its values)
  /// --session FILE: a session (docs/player.md#sessions) to start from instead of the input's
  /// own; a bad one is an error. "": the input's session in the cache folder, if any.
  std::string session;
  bool no_session = false;  ///< --no-session: neither restore nor keep the input's session
  /// The options named on play's command line (--tf, --step, ...): a session does not override
  /// them.
  std::vector<std::string> given;
};

/// Opens the window and runs until it is closed, the script quits or the screenshot is saved.
/// Throws tsp::UsageError (bad step, size), tsp::IoError / tsp::FormatError (files, script),
/// tsp::GlError (no display, no GL 3.3 context).
void run_player(const PlayerOptions& options);

}  // namespace tspplayer
