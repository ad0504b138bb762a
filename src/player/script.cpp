#include "player/script.h"

#include <charconv>
#include <sstream>
#include <utility>

#include "render/settings_table.h"
#include "tsp/clip/probe.h"
#include "tsp/core/error.h"
#include "tsp/core/input_file.h"
#include "tsp/metric/metric.h"

namespace tspplayer {

namespace {

struct LineParser {
  const std::string& origin;
  int line;  // (1-based)
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

// The actions that take on|off, and the command each makes.
using Switch = Command (*)(bool);
constexpr std::pair<const char*, Switch> kSwitches[] = {
    {"loop", [](bool on) -> Command { return cmd::SetLoop{on}; }},
    {"cache", [](bool on) -> Command { return cmd::SetCache{on}; }},
    {"prefetch", [](bool on) -> Command { return cmd::SetPrefetch{on}; }},
    {"lod", [](bool on) -> Command { return cmd::SetLod{on}; }},
    {"show-cut", [](bool on) -> Command { return cmd::ShowCut{on}; }},
    {"panels", [](bool on) -> Command { return cmd::ShowPanels{on}; }},
    {"every-step", [](bool on) -> Command { return cmd::EveryStep{on}; }},
    {"log-opacity", [](bool on) -> Command { return cmd::LogOpacity{on}; }},
    {"probe-surface", [](bool on) -> Command { return cmd::ProbeSurface{on}; }},
    {"expand", [](bool on) -> Command { return cmd::ExpandSections{on}; }}};

// The actions without arguments.
constexpr std::pair<const char*, Command (*)()> kBare[] = {
    {"play", []() -> Command { return cmd::Play{}; }},
    {"pause", []() -> Command { return cmd::Pause{}; }},
    {"quit", []() -> Command { return cmd::Quit{}; }},
    {"reset-camera", []() -> Command { return cmd::ResetCamera{}; }},
    {"probe-clear", []() -> Command { return cmd::ClearProbes{}; }}};

// The actions with one word taken as it is (a path or a name checked when applied).
constexpr std::pair<const char*, const char*> kText[] = {
    {"tf", "tf FILE|preset:NAME"},
    {"tf-range", "tf-range data|bulk|step|view|LO:HI"},
    {"stats", "stats FILE.json"},
    {"screenshot", "screenshot PATH.png"},
    {"screenshot-ui", "screenshot PATH.png"},
    {"lod-filter", "lod-filter error|distance[:K]|fov[:K]"},
    {"field", "field NAME"},
    {"save-session", "save-session PATH"},
    {"capture", "capture DIR|off"},
    {"signal", "signal PATH"}};

Command text_command(const std::string& cmd, const std::string& w) {
  if (cmd == "tf") return cmd::LoadTf{w};
  if (cmd == "tf-range") return cmd::StretchTf{w};
  if (cmd == "stats") return cmd::WriteStats{w};
  if (cmd == "screenshot" || cmd == "screenshot-ui") return cmd::Screenshot{w, cmd != "screenshot"};
  if (cmd == "lod-filter") return cmd::SetLodFilter{w};
  if (cmd == "field") return cmd::ShowField{w};
  if (cmd == "save-session") return cmd::SaveSession{w};
  if (cmd == "signal") return cmd::Signal{w};
  return cmd::Capture{w == "off" ? "" : w};  // capture
}

// The actions with one number.
Command number_command(const LineParser& p) {
  const std::string& cmd = p.words[0];
  const char* usage = cmd == "speed"          ? "speed STEPS_PER_SECOND"
                      : cmd == "quality"      ? "quality DE"
                      : cmd == "zoom"         ? "zoom FACTOR"
                      : cmd == "wait-seconds" ? "wait-seconds S"
                                              : "target-fps FPS";
  p.expect_args(1, usage);
  const double v = p.number(1, usage);
  if (cmd == "speed") return cmd::SetSpeed{v};
  if (cmd == "quality") return cmd::SetQuality{v};
  if (cmd == "zoom") return cmd::SetZoom{v};
  if (cmd == "wait-seconds") return cmd::WaitSeconds{v};
  return cmd::SetTargetFps{v};
}

bool is_number_action(const std::string& cmd) {
  return cmd == "speed" || cmd == "quality" || cmd == "zoom" || cmd == "wait-seconds" ||
         cmd == "target-fps";
}

// open PATH [FIELD] [--OPTION VALUE ...]: the options as play takes them (--raw-dims, …).
Command open_command(const LineParser& p) {
  if (p.words.size() < 2)
    p.fail("'open' takes a path: expected 'open PATH [FIELD] [--OPTION VALUE ...]'");
  cmd::OpenInput o{p.words[1], "", ""};
  std::size_t k = 2;
  if (k < p.words.size() && p.words[k].rfind("--", 0) != 0) o.field = p.words[k++];
  for (; k < p.words.size(); ++k) o.build_options += (o.build_options.empty() ? "" : " ") + p.words[k];
  if (!o.build_options.empty() && o.build_options.rfind("--", 0) != 0)
    p.fail("'open': expected 'open PATH [FIELD] [--OPTION VALUE ...]', found '" + o.build_options +
           "'");
  return o;
}

Command scale_command(const LineParser& p) {
  p.expect_args(1, "scale SX,SY,SZ");
  cmd::SetScale s;
  std::istringstream in(p.words[1]);
  std::string part;
  int n = 0;
  while (std::getline(in, part, ',')) {
    if (n == 3) p.fail("'" + p.words[1] + "': expected SX,SY,SZ");
    LineParser one{p.origin, p.line, {"scale", part}};
    s.factors[std::size_t(n++)] = one.number(1, "scale SX,SY,SZ");
  }
  if (n != 3) p.fail("'" + p.words[1] + "': expected SX,SY,SZ");
  return s;
}

// tf-point move N VALUE OPACITY | colour N R G B A | add VALUE [OPACITY] | remove N
Command tf_point_command(const LineParser& p) {
  const char* usage =
      "tf-point move N VALUE OPACITY|colour N R G B A|add VALUE [OPACITY]|remove N";
  const std::string what = p.words.size() > 1 ? p.words[1] : "";
  const std::size_t n = p.words.size() - 1;
  if (what == "move" && n == 4)
    return cmd::MoveTfPoint{p.integer(2, usage, 1), p.number(3, usage), p.number(4, usage)};
  if (what == "colour" && n == 6)
    return cmd::ColourTfPoint{p.integer(2, usage, 1),
                              {float(p.number(3, usage)), float(p.number(4, usage)),
                               float(p.number(5, usage)), float(p.number(6, usage))}};
  if (what == "add" && (n == 2 || n == 3))
    return cmd::AddTfPoint{p.number(2, usage),
                           n == 3 ? std::optional<double>(p.number(3, usage)) : std::nullopt};
  if (what == "remove" && n == 2) return cmd::RemoveTfPoint{p.integer(2, usage, 1)};
  p.fail("'tf-point': expected '" + std::string(usage) + "'");
}

[[noreturn]] void unknown_action(const LineParser& p) {
  std::string settings;
  for (const tspgl::SettingSpec& spec : tspgl::settings_table())
    settings += std::string(spec.name) + ", ";
  p.fail("unknown action '" + p.words[0] +
         "': expected step, play, pause, speed, loop, tf, tf-range, tolerance, metric, cache, prefetch, "
         "view, zoom, projection, screenshot, screenshot-ui, wait-frames, wait-seconds, " +
         settings +
         "quality, stats, lod, target-fps, lod-filter, show-cut, panels, every-step, log-opacity, open, "
         "field, probe, probe-op, probe-surface, probe-clear, probe-move, record, "
         "reset-camera, playback, capture, save-session, scale, expand, dialog, tf-point, "
         "wait-file, signal or quit");
}

// The actions of two or more arguments, and those checked as they are parsed.
Command other_command(const LineParser& p) {
  const std::string& cmd = p.words[0];
  if (cmd == "step") {
    p.expect_args(1, "step K");
    return cmd::GoToStep{p.integer(1, "step K", 0)};
  }
  if (cmd == "playback") {
    p.expect_args(1, "playback quality|rate");
    return cmd::KeepQuality{p.choice(1, "quality", "rate")};
  }
  if (cmd == "tolerance") {
    p.expect_args(2, "tolerance SPATIAL TEMPORAL");
    return cmd::SetTolerance{p.number(1, "tolerance SPATIAL TEMPORAL"),
                             p.number(2, "tolerance SPATIAL TEMPORAL")};
  }
  if (cmd == "metric") {
    p.expect_args(1, "metric scalar|reference|approximate|perceptual");
    const std::string& m = p.words[1];
    if (m != "scalar" && m != "reference" && m != "approximate" && m != "perceptual")
      p.fail("unknown metric '" + m + "': expected scalar, reference, approximate or perceptual");
    return cmd::SetMetric{tsp::parse_metric(m)};
  }
  if (cmd == "view") {
    p.expect_args(2, "view AZIMUTH ELEVATION");
    return cmd::SetView{p.number(1, "view AZIMUTH ELEVATION"), p.number(2, "view AZIMUTH ELEVATION")};
  }
  if (cmd == "projection") {
    p.expect_args(1, "projection ortho|persp");
    return cmd::SetProjection{p.choice(1, "persp", "ortho")};
  }
  if (cmd == "wait-frames") {
    p.expect_args(1, "wait-frames N");
    return cmd::WaitFrames{p.integer(1, "wait-frames N", 0)};
  }
  if (cmd == "open") return open_command(p);
  if (cmd == "wait-file") {  // wait-file PATH [TIMEOUT_S]
    const char* usage = "wait-file PATH [TIMEOUT_S]";
    if (p.words.size() != 2 && p.words.size() != 3)
      p.fail("'wait-file' takes a path and an optional timeout: expected '" + std::string(usage) +
             "'");
    return cmd::WaitFile{p.words[1],
                         p.words.size() == 3 ? p.number(2, usage) : kDefaultWaitFileSeconds};
  }
  if (cmd == "probe" || cmd == "probe-op") {
    p.expect_args(1, cmd == "probe" ? "probe plane:A,B,C,D|sphere:X,Y,Z,R|box:..."
                                    : "probe-op intersect|union|subtract");
    try {  // checked now: a bad probe is a script error, not a surprise mid-run
      if (cmd == "probe") return cmd::AddProbe{tsp::parse_probe(p.words[1])};
      return cmd::SetProbeOp{tsp::parse_probe_op(p.words[1])};
    } catch (const tsp::UsageError& e) {
      p.fail(e.what());
    }
  }
  if (cmd == "probe-move") {
    const char* usage = "probe-move N DX DY DZ";
    p.expect_args(4, usage);
    return cmd::MoveProbe{p.integer(1, usage, 1),
                          {p.number(2, usage), p.number(3, usage), p.number(4, usage)}};
  }
  if (cmd == "scale") return scale_command(p);
  if (cmd == "tf-point") return tf_point_command(p);
  if (cmd == "dialog") {
    p.expect_args(1, "dialog open|save-tf|record|save-session|close");
    return cmd::ShowDialog{p.words[1]};  // (the word checked by validate())
  }
  if (cmd == "record") {
    p.expect_args(1, "record PATH.mp4|PATH.gif|stop");
    if (p.words[1] == "stop") return cmd::StopRecording{};
    if (!p.words[1].ends_with(".mp4") && !p.words[1].ends_with(".gif"))
      p.fail("'" + p.words[1] + "': expected a .mp4 or .gif file name, or stop");
    return cmd::StartRecording{p.words[1]};
  }
  unknown_action(p);
}

Command parse_words(const LineParser& p) {
  const std::string& cmd = p.words[0];
  for (const auto& [name, make] : kSwitches)
    if (cmd == name) {
      p.expect_args(1, (cmd + " on|off").c_str());
      return make(p.choice(1, "on", "off"));
    }
  for (const auto& [name, make] : kBare)
    if (cmd == name) {
      p.expect_args(0, cmd.c_str());
      return make();
    }
  for (const auto& [name, usage] : kText)
    if (cmd == name) {
      p.expect_args(1, usage);
      return text_command(cmd, p.words[1]);
    }
  if (const tspgl::SettingSpec* spec = tspgl::find_setting(cmd)) {  // the settings table's rows
    const std::string usage = cmd + (spec->kind == tspgl::SettingKind::number ? " VALUE" : " WORD");
    p.expect_args(1, usage.c_str());
    return cmd::SetSetting{cmd, p.words[1]};
  }
  if (is_number_action(cmd)) return number_command(p);
  return other_command(p);
}

}  // namespace

Command parse_command(const std::vector<std::string>& words, const std::string& origin,
                      int line) {
  const LineParser p{origin, line, words};
  if (words.empty()) p.fail("an empty line is not an action");
  Command c = parse_words(p);
  try {  // the values, checked by validate() (the one check keys and panels share)
    validate(c);
  } catch (const tsp::UsageError& e) {
    p.fail(e.what());
  }
  return c;
}

std::vector<ScriptLine> parse_script(const std::string& text, const std::string& origin) {
  std::vector<ScriptLine> actions;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string one; words >> one;) w.push_back(one);
    if (w.empty() || w[0][0] == '#') continue;
    actions.push_back({parse_command(w, origin, number), number});
  }
  return actions;
}

std::vector<ScriptLine> load_script(const std::string& path) {
  return parse_script(tsp::read_input_file(path, "player script"), path);
}

}  // namespace tspplayer
