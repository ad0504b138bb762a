// The player's action script (`tspplay play --script FILE`): one action per line, for tests and
// demos. Format and behaviour: docs/player.md.
#pragma once
#include <string>
#include <vector>

namespace tspplayer {

/// Longest wait-seconds.
inline constexpr double kMaxWaitSeconds = 600;
/// Largest target-fps.
inline constexpr double kMaxTargetFps = 240;
/// Playback speeds accepted, steps per second (the panel's slider spans them too).
inline constexpr double kMinSpeed = 0.25, kMaxSpeed = 60;

/// One player command: a script line, a key or a panel widget makes one, validate() checks it,
/// PlayerApp::apply carries it out — the one path by which the player's state changes.
struct ScriptAction {
  enum class Kind {
    step,           ///< go to step `number` (pauses playback)
    play,           ///< start playback
    pause,          ///< stop playback
    speed,          ///< playback speed `value` steps per second
    loop,           ///< loop on (`flag`) or off
    tf,             ///< transfer function `text`: a file or preset:NAME
    tf_range,       ///< the TF as it is, stretched over `text`: data, histogram, step (the
                    ///< step shown), visible (what the view shows of it) or LO:HI
    tolerance,      ///< spatial `value`, temporal `value2`
    setting,        ///< render setting `text` (a row of render/settings_table.h) set to `text2`
    metric,         ///< metric `text`
    cache,          ///< texture cache on (`flag`) or off
    prefetch,       ///< background brick prefetch on (`flag`) or off
    view,           ///< azimuth `value`, elevation `value2` (degrees)
    zoom,           ///< zoom `value` (> 0)
    projection,     ///< perspective (`flag`) or orthographic
    screenshot,     ///< save the next complete frame (volume only) to `text`
    screenshot_ui,  ///< save the next complete frame with the UI panels to `text`
    wait_frames,    ///< let `number` frames pass
    wait_seconds,   ///< let `value` seconds pass (frames keep running)
    quality,        ///< quality target mean ΔE `value` (calibrates once; blocks)
    stats,          ///< write the HUD statistics (frame times, fps, last frame) to `text` (JSON)
    lod,            ///< the LOD cut on (`flag`) or off
    target_fps,     ///< LOD target `value` frames per second while interacting
    lod_filter,     ///< how the cut is chosen: `text` error|distance[:K]|fov[:K] (LaMar's filters)
    show_cut,       ///< outline the cut's nodes by level on (`flag`) or off
    panels,         ///< the UI panels shown (`flag`) or hidden (the volume fills the window)
    every_step,     ///< playback shows every step (`flag`) or keeps real time, dropping steps
    log_opacity,    ///< the TF editor's opacity axis logarithmic (`flag`) or linear
    open,           ///< open `text` (a .tsp file or any build input; field `text2`), waiting
    field,          ///< show the file's field `text`
    probe,          ///< add the clip probe `text` (as render --probe)
    probe_op,       ///< how the probes combine: `text` intersect|union|subtract
    probe_surface,  ///< draw the clip surface (`flag`)
    probe_clear,    ///< remove every probe
    probe_move,     ///< move probe `number` (1-based) by `value`, `value2`, `value3` (physical)
    record,         ///< start recording a movie to `text` (.mp4 or .gif)
    record_stop,    ///< stop recording and write the movie (waits for the encoder)
    reset_camera,   ///< the camera back to where it started (key R)
    playback,       ///< while playing with a quality target, keep quality (`flag`) or the rate
    capture,        ///< save every frame as drawn to folder `text` (frame_NNNN.png and a line in
                    ///< frames.jsonl each), not waiting for full quality; "off" stops
    quit,           ///< close the player
    save_session,   ///< save the session (TF, view, probes, ...) to `text` (docs/player.md#sessions)
    scale,          ///< stretch the axes by `value`, `value2`, `value3` (as --scale)
    expand          ///< every section of the panels open (`flag`), or as they start
  };
  Kind kind = Kind::quit;
  int number = 0;
  double value = 0, value2 = 0, value3 = 0;
  bool flag = false;
  std::string text, text2;
  std::string text3;  ///< `open`: build options, as on play's command line (may be empty)
  int line = 0;  ///< 1-based line in the script, for messages
};

/// A command of kind `kind` with flag `flag` (play, pause, loop, panels, ...). Never throws.
ScriptAction command_of(ScriptAction::Kind kind, bool flag = false);
/// The command "go to step t". Never throws.
ScriptAction step_command(int t);

/// True when the script stops after action a until frames pass: a screenshot, `wait-frames N`
/// with N > 0 or `wait-seconds S` with S > 0 (a wait of 0 is free: it used to cost a frame, and
/// a script of a million `wait-frames 0` lines ran for 45 minutes). Never throws.
bool waits_for_frames(const ScriptAction& a);

/// Checks an action's values (speed, tolerances, view, zoom, waits, targets, render settings)
/// whoever made it — a script line, a key or a panel: the one validation of player commands.
/// Throws tsp::UsageError naming the action and what it accepts.
void validate(const ScriptAction& a);

/// Parses script text; origin names it in messages. Blank lines and lines starting with '#' are
/// skipped. Throws tsp::FormatError naming origin, the line and what was expected.
std::vector<ScriptAction> parse_script(const std::string& text, const std::string& origin);
/// Reads (through tsp::read_input_file: a regular file of at most 64 MiB) and parses a script
/// file. Throws tsp::IoError when it is not such a file or unreadable, else like parse_script.
std::vector<ScriptAction> load_script(const std::string& path);

}  // namespace tspplayer
