#include "player/script.h"

#include <charconv>
#include <cmath>
#include <sstream>
#include <utility>

#include "jobs/render_job.h"
#include "render/settings_table.h"
#include "tsp/clip/probe.h"
#include "tsp/core/error.h"
#include "tsp/metric/tf_io.h"
#include "tsp/core/input_file.h"
#include "tsp/lod/selection_filter.h"

namespace tspplayer {

namespace {

using Kind = ScriptAction::Kind;

// Quality limit, as `tspplay render --quality` accepts it.
constexpr double kMaxQuality = 50;

struct LineParser {
  const std::string& origin;
  int line;
  std::vector<std::string> words;

  [[noreturn]] void fail(const std::string& what) const {
    throw tsp::FormatError(origin + ":" + std::to_string(line) + ": " + what);
  }
  void expect_args(std::size_t n, const char* usage) const {
    if (words.size() != n + 1)
      fail("'" + words[0] + "' takes " + std::to_string(n) + " argument(s): expected '" + usage +
           "', found " + std::to_string(words.size() - 1));
  }
  double number(std::size_t i, const char* usage) const {
    const std::string& w = words[i];
    double v = 0;
    auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
    if (ec != std::errc() || end != w.data() + w.size())
      fail("'" + w + "' is not a number (expected '" + usage + "')");
    return v;
  }
  int integer(std::size_t i, const char* usage, int lo) const {
    const std::string& w = words[i];
    int v = 0;
    auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
    if (ec != std::errc() || end != w.data() + w.size() || v < lo)
      fail("'" + w + "' is not an integer >= " + std::to_string(lo) + " (expected '" + usage +
           "')");
    return v;
  }
  bool choice(std::size_t i, const char* yes, const char* no) const {
    if (words[i] == yes) return true;
    if (words[i] == no) return false;
    fail("'" + words[i] + "': expected " + yes + " or " + no);
  }
};

// The actions that take on|off.
constexpr std::pair<const char*, Kind> kSwitches[] = {
    {"loop", Kind::loop},           {"cache", Kind::cache}, {"prefetch", Kind::prefetch},
    {"lod", Kind::lod},     {"show-cut", Kind::show_cut},
    {"panels", Kind::panels},       {"every-step", Kind::every_step},
    {"log-opacity", Kind::log_opacity}, {"probe-surface", Kind::probe_surface},
    {"expand", Kind::expand}};

ScriptAction parse_words(const LineParser& p) {
  ScriptAction a;
  a.line = p.line;
  const std::string& cmd = p.words[0];
  for (const auto& [name, kind] : kSwitches)
    if (cmd == name) {
      p.expect_args(1, (cmd + " on|off").c_str());
      a.kind = kind;
      a.flag = p.choice(1, "on", "off");
      return a;
    }
  if (const tspgl::SettingSpec* spec = tspgl::find_setting(cmd)) {  // the settings table's rows
    const std::string usage = cmd + (spec->kind == tspgl::SettingKind::number ? " VALUE" : " WORD");
    p.expect_args(1, usage.c_str());
    a.kind = Kind::setting;
    a.text = cmd;
    a.text2 = p.words[1];
  } else if (cmd == "step") {
    p.expect_args(1, "step K");
    a.kind = Kind::step;
    a.number = p.integer(1, "step K", 0);
  } else if (cmd == "play" || cmd == "pause" || cmd == "quit" || cmd == "reset-camera") {
    p.expect_args(0, cmd.c_str());
    a.kind = cmd == "play"    ? Kind::play
             : cmd == "pause" ? Kind::pause
             : cmd == "quit"  ? Kind::quit
                              : Kind::reset_camera;
  } else if (cmd == "playback") {
    p.expect_args(1, "playback quality|rate");
    a.kind = Kind::playback;
    a.flag = p.choice(1, "quality", "rate");
  } else if (cmd == "speed") {
    p.expect_args(1, "speed STEPS_PER_SECOND");
    a.kind = Kind::speed;
    a.value = p.number(1, "speed STEPS_PER_SECOND");
  } else if (cmd == "tf") {
    p.expect_args(1, "tf FILE|preset:NAME");
    a.kind = Kind::tf;
    a.text = p.words[1];
  } else if (cmd == "tf-range") {
    p.expect_args(1, "tf-range data|histogram|step|visible|LO:HI");
    a.kind = Kind::tf_range;
    a.text = p.words[1];
  } else if (cmd == "tolerance") {
    p.expect_args(2, "tolerance SPATIAL TEMPORAL");
    a.kind = Kind::tolerance;
    a.value = p.number(1, "tolerance SPATIAL TEMPORAL");
    a.value2 = p.number(2, "tolerance SPATIAL TEMPORAL");
  } else if (cmd == "metric") {
    p.expect_args(1, "metric scalar|reference|approximate|perceptual");
    a.kind = Kind::metric;
    a.text = p.words[1];
    if (a.text != "scalar" && a.text != "reference" && a.text != "approximate" &&
        a.text != "perceptual")
      p.fail("unknown metric '" + a.text +
             "': expected scalar, reference, approximate or perceptual");
  } else if (cmd == "view") {
    p.expect_args(2, "view AZIMUTH ELEVATION");
    a.kind = Kind::view;
    a.value = p.number(1, "view AZIMUTH ELEVATION");
    a.value2 = p.number(2, "view AZIMUTH ELEVATION");
  } else if (cmd == "quality") {
    p.expect_args(1, "quality DE");
    a.kind = Kind::quality;
    a.value = p.number(1, "quality DE");
  } else if (cmd == "stats") {
    p.expect_args(1, "stats FILE.json");
    a.kind = Kind::stats;
    a.text = p.words[1];
  } else if (cmd == "zoom") {
    p.expect_args(1, "zoom FACTOR");
    a.kind = Kind::zoom;
    a.value = p.number(1, "zoom FACTOR");
  } else if (cmd == "projection") {
    p.expect_args(1, "projection ortho|persp");
    a.kind = Kind::projection;
    a.flag = p.choice(1, "persp", "ortho");
  } else if (cmd == "screenshot" || cmd == "screenshot-ui") {
    p.expect_args(1, "screenshot PATH.png");
    a.kind = cmd == "screenshot" ? Kind::screenshot : Kind::screenshot_ui;
    a.text = p.words[1];
  } else if (cmd == "wait-frames") {
    p.expect_args(1, "wait-frames N");
    a.kind = Kind::wait_frames;
    a.number = p.integer(1, "wait-frames N", 0);
  } else if (cmd == "wait-seconds") {
    p.expect_args(1, "wait-seconds S");
    a.kind = Kind::wait_seconds;
    a.value = p.number(1, "wait-seconds S");
  } else if (cmd == "target-fps") {
    p.expect_args(1, "target-fps FPS");
    a.kind = Kind::target_fps;
    a.value = p.number(1, "target-fps FPS");
  } else if (cmd == "lod-filter") {
    p.expect_args(1, "lod-filter error|distance[:K]|fov[:K]");
    a.kind = Kind::lod_filter;
    a.text = p.words[1];
  } else if (cmd == "open") {
    // open PATH [FIELD] [--OPTION VALUE ...]: the options as play takes them (--raw-dims, …).
    if (p.words.size() < 2)
      p.fail("'open' takes a path: expected 'open PATH [FIELD] [--OPTION VALUE ...]'");
    a.kind = Kind::open;
    a.text = p.words[1];
    std::size_t k = 2;
    if (k < p.words.size() && p.words[k].rfind("--", 0) != 0) a.text2 = p.words[k++];
    for (; k < p.words.size(); ++k) a.text3 += (a.text3.empty() ? "" : " ") + p.words[k];
    if (!a.text3.empty() && a.text3.rfind("--", 0) != 0)
      p.fail("'open': expected 'open PATH [FIELD] [--OPTION VALUE ...]', found '" + a.text3 + "'");
  } else if (cmd == "probe" || cmd == "probe-op") {
    p.expect_args(1, cmd == "probe" ? "probe plane:A,B,C,D|sphere:X,Y,Z,R|box:..."
                                    : "probe-op intersect|union|subtract");
    a.kind = cmd == "probe" ? Kind::probe : Kind::probe_op;
    a.text = p.words[1];
    try {  // checked now: a bad probe is a script error, not a surprise mid-run
      if (a.kind == Kind::probe)
        tsp::parse_probe(a.text);
      else
        tsp::parse_probe_op(a.text);
    } catch (const tsp::UsageError& e) {
      p.fail(e.what());
    }
  } else if (cmd == "probe-clear") {
    p.expect_args(0, "probe-clear");
    a.kind = Kind::probe_clear;
  } else if (cmd == "probe-move") {
    p.expect_args(4, "probe-move N DX DY DZ");
    a.kind = Kind::probe_move;
    a.number = p.integer(1, "probe-move N DX DY DZ", 1);
    a.value = p.number(2, "probe-move N DX DY DZ");
    a.value2 = p.number(3, "probe-move N DX DY DZ");
    a.value3 = p.number(4, "probe-move N DX DY DZ");
  } else if (cmd == "field") {
    p.expect_args(1, "field NAME");
    a.kind = Kind::field;
    a.text = p.words[1];
  } else if (cmd == "save-session") {
    p.expect_args(1, "save-session PATH");
    a.kind = Kind::save_session;
    a.text = p.words[1];
  } else if (cmd == "scale") {
    p.expect_args(1, "scale SX,SY,SZ");
    a.kind = Kind::scale;
    double v[3];
    std::istringstream in(p.words[1]);
    std::string part;
    int n = 0;
    while (std::getline(in, part, ',')) {
      if (n == 3) p.fail("'" + p.words[1] + "': expected SX,SY,SZ");
      LineParser one{p.origin, p.line, {"scale", part}};
      v[n++] = one.number(1, "scale SX,SY,SZ");
    }
    if (n != 3) p.fail("'" + p.words[1] + "': expected SX,SY,SZ");
    a.value = v[0];
    a.value2 = v[1];
    a.value3 = v[2];
  } else if (cmd == "record") {
    p.expect_args(1, "record PATH.mp4|PATH.gif|stop");
    a.kind = p.words[1] == "stop" ? Kind::record_stop : Kind::record;
    a.text = p.words[1];
    if (a.kind == Kind::record && !p.words[1].ends_with(".mp4") && !p.words[1].ends_with(".gif"))
      p.fail("'" + p.words[1] + "': expected a .mp4 or .gif file name, or stop");
  } else if (cmd == "capture") {
    p.expect_args(1, "capture DIR|off");
    a.kind = Kind::capture;
    a.text = p.words[1];
  } else {
    std::string settings;
    for (const tspgl::SettingSpec& spec : tspgl::settings_table())
      settings += std::string(spec.name) + ", ";
    p.fail("unknown action '" + cmd +
           "': expected step, play, pause, speed, loop, tf, tf-range, tolerance, metric, cache, prefetch, "
           "view, zoom, projection, screenshot, screenshot-ui, wait-frames, wait-seconds, " +
           settings +
           "quality, stats, lod, target-fps, lod-filter, show-cut, panels, every-step, log-opacity, open, "
           "field, probe, probe-op, probe-surface, probe-clear, probe-move, record, "
           "reset-camera, playback, capture, save-session, scale, expand or quit");
  }
  return a;
}

// A line's action, its values checked by validate() (the one check keys and panels share).
ScriptAction parse_line(const LineParser& p) {
  const ScriptAction a = parse_words(p);
  try {
    validate(a);
  } catch (const tsp::UsageError& e) {
    p.fail(e.what());
  }
  return a;
}

}  // namespace

ScriptAction command_of(ScriptAction::Kind kind, bool flag) {
  ScriptAction a;
  a.kind = kind;
  a.flag = flag;
  return a;
}

ScriptAction step_command(int t) {
  ScriptAction a;
  a.kind = ScriptAction::Kind::step;
  a.number = t;
  return a;
}

bool waits_for_frames(const ScriptAction& a) {
  switch (a.kind) {
    case Kind::screenshot:
    case Kind::screenshot_ui:
      return true;
    case Kind::wait_frames:
      return a.number > 0;
    case Kind::wait_seconds:
      return a.value > 0;
    default:
      return false;
  }
}

void validate(const ScriptAction& a) {
  auto fail = [](const std::string& what) { throw tsp::UsageError(what); };
  switch (a.kind) {
    case Kind::speed:
      if (!(a.value >= kMinSpeed && a.value <= kMaxSpeed))
        fail("speed must be positive: " + std::to_string(kMinSpeed).substr(0, 4) + " to " +
             std::to_string(int(kMaxSpeed)) + " steps per second");
      break;
    case Kind::tf_range: {
      const tsp::TfRangeChoice c = tsp::parse_tf_range(a.text);  // throws UsageError
      if (c.mode != tsp::TfRangeChoice::Mode::data && c.mode != tsp::TfRangeChoice::Mode::histogram &&
          c.mode != tsp::TfRangeChoice::Mode::step && c.mode != tsp::TfRangeChoice::Mode::visible &&
          c.mode != tsp::TfRangeChoice::Mode::explicit_range)
        fail("tf-range '" + a.text +
             "': the map shown is stretched over data, histogram, step, visible or LO:HI");
      break;
    }
    case Kind::tolerance:
      if (!(a.value >= 0) || !(a.value2 >= 0) || !std::isfinite(a.value) || !std::isfinite(a.value2))
        fail("tolerances must be finite and not negative");
      break;
    case Kind::view:
      if (!std::isfinite(a.value)) fail("azimuth must be finite");
      if (!(a.value2 > -90 && a.value2 < 90)) fail("elevation must be in (-90, 90) degrees");
      break;
    case Kind::quality:
      if (!(a.value >= 0) || a.value > kMaxQuality)
        fail("quality must be a mean dE in [0, 50] (0: off)");
      break;
    case Kind::zoom:
      if (!(a.value > 0) || !std::isfinite(a.value)) fail("zoom must be positive and finite");
      break;
    case Kind::wait_seconds:
      if (!(a.value >= 0) || a.value > kMaxWaitSeconds)
        fail("wait-seconds must be 0 to " + std::to_string(int(kMaxWaitSeconds)) + " seconds");
      break;
    case Kind::target_fps:
      if (!(a.value >= 1 && a.value <= kMaxTargetFps))
        fail("target-fps must be 1 to " + std::to_string(int(kMaxTargetFps)) +
             " frames per second");
      break;
    case Kind::lod_filter:
      tsp::parse_lod_filter(a.text, "lod-filter");  // (throws UsageError naming it)
      break;
    case Kind::scale:
      for (double k : {a.value, a.value2, a.value3})
        if (!(k > 0) || !(k <= tspgl::kMaxScale))
          fail("scale: expected three factors in (0, " + std::to_string(int(tspgl::kMaxScale)) + "]");
      break;
    case Kind::probe_move:
      if (!std::isfinite(a.value) || !std::isfinite(a.value2) || !std::isfinite(a.value3))
        fail("probe-move: the displacement must be finite");
      break;
    case Kind::setting: {
      const tspgl::SettingSpec* spec = tspgl::find_setting(a.text);
      if (!spec) fail("no render setting '" + a.text + "'");
      tspgl::RenderSettings scratch;
      tspgl::set_setting(scratch, *spec, a.text2, a.text);
      break;
    }
    default:
      break;
  }
}

std::vector<ScriptAction> parse_script(const std::string& text, const std::string& origin) {
  std::vector<ScriptAction> actions;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream words(line);
    LineParser p{origin, number, {}};
    for (std::string w; words >> w;) p.words.push_back(w);
    if (p.words.empty() || p.words[0][0] == '#') continue;
    actions.push_back(parse_line(p));
  }
  return actions;
}

std::vector<ScriptAction> load_script(const std::string& path) {
  return parse_script(tsp::read_input_file(path, "player script"), path);
}

}  // namespace tspplayer
