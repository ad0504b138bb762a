// The player's sessions (issue 47 item 4): what the window shows, kept per input and field in the
// cache folder when it quits or opens another input, restored when the same input is played
// again; saved anywhere (File > Save session..., save-session PATH) and started from with
// play --session FILE. The file's format: player/session.h, docs/player.md#sessions.
#include <imgui.h>
#include <imgui_internal.h>  // the windows' state storage: which sections are open

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "player/export_names.h"
#include "player/player_app.h"
#include "player/session.h"
#include "tsp/core/error.h"

namespace tspplayer {

namespace {

namespace fs = std::filesystem;

// Which tree nodes and collapsing headers of each window are open: Dear ImGui keeps them in the
// window's state storage by ID (the label's hash), 0 or 1. Child windows count (the side panel's
// sections scroll in "##side/##sections_…", above its fixed status area); popups and tooltips
// do not. Windows with none toggled hold nothing.
nlohmann::json open_sections() {
  nlohmann::json out = nlohmann::json::object();
  const ImGuiContext* g = ImGui::GetCurrentContext();
  if (!g) return out;
  for (const ImGuiWindow* w : g->Windows) {
    if (w->Flags & (ImGuiWindowFlags_Popup | ImGuiWindowFlags_Tooltip))
      continue;
    nlohmann::json ids = nlohmann::json::array();
    for (const ImGuiStorage::ImGuiStoragePair& p : w->StateStorage.Data)
      if (p.val_i == 0 || p.val_i == 1) ids.push_back({std::int64_t(p.key), p.val_i});
    if (!ids.empty()) out[w->Name] = ids;
  }
  return out;
}

// The input as the user named it, absolute (the session's key and its "input").
std::string named_input(const std::string& given) {
  std::error_code ec;
  const fs::path p = fs::absolute(fs::path(given), ec);
  return (ec ? fs::path(given) : p).lexically_normal().string();
}

}  // namespace

Session PlayerApp::capture_session() const {
  Session s;
  s.input = session_input_;
  s.field = field();
  s.tf_domain = tf.domain();
  s.tf_entries.assign(tf.entries().begin(), tf.entries().end());
  s.tf_points = tf_points_;
  s.tf_label = tf_label;
  s.log_opacity = state_.log_opacity;
  const tsp::CameraParams& c = state_.camera;
  s.azimuth_deg = c.azimuth_deg;
  s.elevation_deg = c.elevation_deg;
  s.zoom = c.zoom;
  s.fov_deg = c.fov_deg;
  s.perspective = c.projection == tsp::Projection::perspective;
  s.pan = c.pan;
  s.eye = c.eye;
  s.scale = options_.scale;
  s.step = state_.step;
  s.speed = speed_chosen_ ? state_.speed : 0;  // (0: the series' default, whatever its length)
  s.loop = state_.loop;
  s.every_step = state_.every_step;
  for (const tsp::Probe& p : state_.probes) s.probes.push_back(tsp::to_string(p));
  s.probe_op = tsp::to_string(state_.probe_op);
  s.probe_surface = state_.probe_surface;
  s.surface = state_.settings.surface;
  s.panels = state_.panels;
  s.annotations = state_.annotations;
  if (imgui_) {
    s.ui_ini = ImGui::SaveIniSettingsToMemory();
    s.ui_open = open_sections();
    for (const auto& [window, ids] : pending_ui_open_.items())  // not drawn since restored
      if (!s.ui_open.contains(window)) s.ui_open[window] = ids;
  }
  return s;
}

void PlayerApp::check_session(const Session& s, const std::string& origin) const {
  const std::vector<std::string>& names = viewer_->file().fields();
  if (!s.field.empty() && std::find(names.begin(), names.end(), s.field) == names.end())
    throw tsp::FormatError(origin + ": the session shows the field '" + s.field + "', which " +
                           options_.tsp_path + " does not hold");
  try {
    std::vector<tsp::Probe> probes;
    for (const std::string& text : s.probes) probes.push_back(tsp::parse_probe(text));
    (void)tsp::ClipRegion(probes, tsp::parse_probe_op(s.probe_op), viewer_->file().metadata().origin,
                          viewer_->file().metadata().spacing);
    if (!s.tf_entries.empty()) (void)tsp::TransferFunction(s.tf_domain, int(s.tf_entries.size()));
  } catch (const tsp::Error& e) {
    throw tsp::FormatError(origin + ": " + e.what());
  }
}

void PlayerApp::apply_session(const Session& s, bool command_line) {
  // What play's command line named wins over the session it starts from.
  auto given = [&](const char* option) {
    return command_line && std::find(options_.given.begin(), options_.given.end(), option) !=
                               options_.given.end();
  };
  if (!s.field.empty() && s.field != field() && !given("--field")) switch_field(s.field);
  if (!given("--scale")) set_scale(s.scale);
  tsp::CameraParams& c = state_.camera;
  c.azimuth_deg = s.azimuth_deg;
  c.elevation_deg = s.elevation_deg;
  c.zoom = s.zoom;
  c.fov_deg = s.fov_deg;
  c.projection = s.perspective ? tsp::Projection::perspective : tsp::Projection::orthographic;
  c.pan = s.pan;
  c.eye = s.eye;
  if (!s.tf_entries.empty() && !given("--tf") && !given("--tf-range")) {
    tsp::TransferFunction next(s.tf_domain, int(s.tf_entries.size()));
    next.set_entries(0, s.tf_entries);
    set_tf(next, s.tf_points.empty());
    if (!s.tf_points.empty()) {  // the saved handles, placed over the restored map
      tf_points_ = s.tf_points;
      tf_handles_ = {tf, tf_points_};
    }
    tf_label = s.tf_label;
  }
  state_.log_opacity = s.log_opacity;
  if (!given("--step")) state_.step = std::clamp(s.step, 0, steps() - 1);
  if (s.speed > 0 && !given("--speed")) {
    state_.speed = std::clamp(s.speed, kMinSpeed, kMaxSpeed);
    speed_chosen_ = true;
  }
  state_.loop = s.loop;
  state_.every_step = s.every_step;
  if (!given("--probe") && !given("--probe-op") && !given("--probe-surface")) {
    state_.probes.clear();
    for (const std::string& text : s.probes) state_.probes.push_back(tsp::parse_probe(text));
    state_.probe_op = tsp::parse_probe_op(s.probe_op);
    state_.probe_surface = s.probe_surface;
    probe_selected_ = state_.probes.empty() ? -1 : 0;
    probes_changed();
  }
  if (!given("--surface") && s.surface != state_.settings.surface)
    set_setting("surface", s.surface ? "boundary" : "off");  // (says so when no mesh is at hand)
  state_.panels = s.panels;
  state_.annotations = s.annotations;
  if (imgui_ && frames_drawn_ == 0 && !s.ui_ini.empty())  // (places windows not made yet)
    ImGui::LoadIniSettingsFromMemory(s.ui_ini.data(), s.ui_ini.size());
  pending_ui_open_ = s.ui_open;
}

void PlayerApp::apply_pending_ui() {
  if (options_.trace) {  // (toggled in the last frame, or restored)
    const std::string now = open_sections().dump();
    if (now != traced_sections_) trace("open sections " + now);
    traced_sections_ = now;
  }
  if (pending_ui_open_.empty()) return;
  for (auto it = pending_ui_open_.begin(); it != pending_ui_open_.end();) {
    ImGuiWindow* w = ImGui::FindWindowByName(it.key().c_str());
    if (!w) {
      ++it;
      continue;
    }
    for (const nlohmann::json& pair : *it)
      w->StateStorage.SetInt(ImGuiID(pair[0].get<std::int64_t>()), pair[1].get<int>());
    it = pending_ui_open_.erase(it);
  }
}

void PlayerApp::restore_session(bool at_start) {
  session_input_ =
      named_input(options_.input_path.empty() ? options_.tsp_path : options_.input_path);
  session_file_ =
      options_.no_session ? "" : session_cache_path(session_input_, field(), options_.cache_dir);
  session_from_.clear();
  session_note_.clear();
  if (at_start && !options_.session.empty()) {  // a shared session: its errors are play's
    const Session s = read_session(options_.session);
    check_session(s, options_.session);
    apply_session(s, true);
    session_from_ = options_.session;
  } else if (std::error_code ec; !session_file_.empty() &&
                                 fs::exists(fs::symlink_status(session_file_, ec))) {
    try {
      const Session s = read_session(session_file_);
      check_session(s, session_file_);
      apply_session(s, at_start);
      session_from_ = session_file_;
    } catch (const tsp::Error& e) {  // bad or foreign: defaults; the file is left as it is
      session_note_ = std::string(e.what()) +
                      "; session ignored, opening with defaults (the file is replaced only "
                      "when this window saves its session)";
      status = session_note_;
      std::fprintf(stderr, "tspplay: warning: %s\n", session_note_.c_str());
    }
  }
  if (!session_from_.empty()) {
    status = "restored session from " + session_from_;
    if (options_.trace) {
      std::printf("trace: %s\n", status.c_str());
      std::fflush(stdout);
    }
  }
}

void PlayerApp::save_session_entry() {
  if (session_file_.empty()) return;
  try {
    write_session(session_file_, capture_session(), true);
  } catch (const tsp::Error& e) {  // the window goes on (or ends); the next one starts afresh
    status = std::string("session not kept: ") + e.what();
    std::fprintf(stderr, "tspplay: %s\n", status.c_str());
  }
}

void PlayerApp::save_session_as(const std::string& path) {
  try {
    write_session(path, capture_session(), false);
    status = "saved session " + path;
    last_session_folder_ = std::filesystem::path(path).parent_path().string();
    last_saved_folder_ = std::filesystem::absolute(path).parent_path().string();
  } catch (const tsp::Error& e) {
    status = e.what();
    std::fprintf(stderr, "tspplay: %s\n", e.what());
  }
}

nlohmann::json PlayerApp::session_json() const {
  return {{"restored", !session_from_.empty()},
          {"from", session_from_},
          {"file", session_file_},
          {"ignored", session_note_},
          {"open_sections", open_sections()}};  // as the windows hold them now
}

std::string PlayerApp::session_offer() const {
  // (It offered tspplay_session.json in the working directory, whatever was played.)
  const std::string given = options_.input_path.empty() ? options_.tsp_path : options_.input_path;
  const std::string folder = last_session_folder_.empty() ? open_folder() : last_session_folder_;
  const std::string name = dataset_name(given) + ".session.json";
  return folder.empty() ? name : (std::filesystem::path(folder) / name).string();
}

}  // namespace tspplayer
