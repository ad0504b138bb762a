// `tspplay render`'s options as text, and their one mapping onto the job's options: the CLI and
// the Python module (src/python) both go through render_job_options, so every check and message
// is the same.
#pragma once
#include <string>
#include <vector>

#include "cli/session_options.h"
#include "jobs/movie.h"
#include "jobs/render_job.h"
#include "render/render_settings.h"

namespace tspcli {

/// `render`'s options besides the settings table, as the command line gives them (text, as
/// typed; numbers where CLI11 parses them): the session options' shared fields (SessionArgs,
/// session_options.h) and render's own. The defaults are the command's.
struct RenderArgs : SessionArgs {
  /// render's defaults: the table's (session_defaults) and its own below.
  RenderArgs() : SessionArgs(session_defaults(SessionCommand::render)) {}
  std::string file, out, steps, movie;
  int fps = tspgl::kMovieFps;
  std::string annotate = "off";
  std::string metric = "approximate", cache = "on";
  int passes = 1;
  std::string baseline = "off", perspective = "off";
  std::string calibration_dir, save_tf;
  double target_ms = 0, orbit = 0;
  int split_limit = tsp::LodOptions{}.split_limit;
  std::string focus, eye;
  std::string probe_tf, probe_motion;
  double surface_target_ms = 0;
};

/// Largest --target-fps (as play's).
inline constexpr double kMaxTargetFps = 240;

/// The long names of RenderArgs' options, as `render` takes them ("tf-range", "probe", …; the
/// input file is "file", -o is "output"). Never throws.
std::vector<std::string> render_arg_names();

/// Sets option `name` (a render_arg_names() entry) of a from text as the command line would:
/// numbers parsed whole (tsp::UsageError naming --NAME otherwise), "probe" appended. Returns
/// false, changing nothing, for an unknown name.
bool set_render_arg(RenderArgs& a, const std::string& name, const std::string& text);

/// The job `render` runs for a, drawn with settings (the settings table's knobs, already parsed
/// and validated); given_settings: the table's options given explicitly ("--spacing", …), which
/// --quality refuses. Checks every option but -o (empty: no frames folder) (and, with --movie, that ffmpeg is on PATH) before
/// anything is opened. Throws tsp::UsageError naming the option, the text and what it accepts;
/// tsp::IoError when --movie has no ffmpeg. Never touches files otherwise; thread-safe.
tspgl::RenderJobOptions render_job_options(const RenderArgs& a, const tspgl::RenderSettings& settings,
                                           const std::vector<std::string>& given_settings);

}  // namespace tspcli
