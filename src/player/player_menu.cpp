// The player's menu bar and the dialogs it opens: File > Open (a folder browser over any input
// `build` reads, with a progress dialog while an input builds), save the TF as, record a movie.
// Our loader (gl/gl_api.h) declares the GL functions; GLFW must not pull in GL/gl.h.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "jobs/play_input.h"
#include "player/player_app.h"
#include "tsp/core/temp_output.h"
#include "player/player_ui.h"
#include "player/ui_items.h"

namespace tspplayer {

namespace {

namespace fs = std::filesystem;

constexpr int kPathChars = 1024;
constexpr float kBrowserHeight = 240.f;
constexpr const char* kOpenPopup = "Open";
constexpr const char* kTfPopup = "Save transfer function as";
constexpr const char* kRecordPopup = "Record movie";
constexpr const char* kProgressPopup = "Opening";
constexpr const char* kSessionPopup = "Save session";

// The open dialog's folder listing: folders first, then files, names sorted; hidden entries left
// out. Read again only when the folder changes.
struct Listing {
  fs::path dir;
  std::vector<std::pair<std::string, bool>> entries;  // name, is a folder
  std::string error;

  void read(const fs::path& d) {
    dir = d;
    entries.clear();
    error.clear();
    std::error_code ec;
    for (fs::directory_iterator it(d, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string name = it->path().filename().string();
      if (name.empty() || name[0] == '.') continue;
      std::error_code e2;
      entries.push_back({name, it->is_directory(e2)});
    }
    if (ec) error = d.string() + ": " + ec.message();
    std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
      return a.second != b.second ? a.second : a.first < b.first;
    });
  }
};

struct MenuState {
  bool want_open = false, want_tf = false, want_record = false;
  bool all_files = false;  // the open dialog lists every file, not only the kinds play reads
  char open_path[kPathChars] = "";
  char field[128] = "";
  bool focus_path = false;  // the dialog just opened: its path field takes the keys
  char build_options[kPathChars] = "";  // File > Open: --raw-dims 64,64,64 --raw-type f32, …
  char tf_path[kPathChars] = "";
  char movie_path[kPathChars] = "";  // (offered as the dialog opens: NAME_FIELD.mp4)
  Listing listing;
  bool want_session = false;
  std::string traced_list;    // the last "open list X Y ROW" traced
  bool clicked_into = false;  // this click sequence changed the folder (its next clicks are not for the new list)
  char session_path[kPathChars] = "";  // (offered as the dialog opens: DATASET.session.json)
  bool want_close = false;  // script `dialog close`: the dialog open closes, as Cancel
  // File > Open stays open until its open ends: closed when it succeeded, or when a build
  // started (the progress dialog takes over; reopened if the build fails), else the error is
  // shown in it with the path kept.
  bool awaiting = false;           // Open pressed: the command is applied after this frame
  bool reopen_on_failure = false;  // a build it started is running
  std::uint64_t outcome_seen = 0;  // PlayerApp::open_outcome().ended when Open was pressed
  std::string open_error;          // the failed open's error, shown in red
  bool close_open = false;         // the open succeeded (or a build started): the dialog closes
};

MenuState& state() {
  static MenuState s;
  return s;
}

void copy(char* to, std::size_t size, const std::string& from) {
  std::snprintf(to, size, "%s", from.c_str());
}

bool key_pressed(ImGuiKey key) { return ImGui::IsKeyPressed(ImGui::GetKeyIndex(key), false); }

// Escape pressed while this dialog (not a combo over it) has the keys: it closes, as Cancel.
bool escape_closes() {
  return key_pressed(ImGuiKey_Escape) && ImGui::IsWindowFocused(ImGuiFocusedFlags_RootAndChildWindows);
}

// Script `dialog close` asked the dialog open to close (once).
bool take_close() {
  const bool close = state().want_close;
  state().want_close = false;
  return close;
}

// The text field just drawn was left with Enter (Dear ImGui ends the edit on Enter).
bool entered() {
  return ImGui::IsItemDeactivated() && (key_pressed(ImGuiKey_Enter) || key_pressed(ImGuiKey_KeyPadEnter));
}

void menu_bar(PlayerApp& app) {
  MenuState& s = state();
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("Open...", "Ctrl+O")) s.want_open = true;
    if (ImGui::MenuItem("Save transfer function as...")) s.want_tf = true;
    if (!app.recording()) {
      if (ImGui::MenuItem("Record movie...")) s.want_record = true;
    } else if (ImGui::MenuItem("Stop recording")) {
      app.push(cmd::StopRecording{});
    }
    if (ImGui::MenuItem("Save PNG", "S")) app.push(cmd::SavePicture{});
    if (ImGui::MenuItem("Save session...")) s.want_session = true;
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q"))
      glfwSetWindowShouldClose(static_cast<GLFWwindow*>(app.ctx->native_window()), 1);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    if (ImGui::MenuItem("Panels", "Tab", app.state().panels))
      app.push(cmd::ShowPanels{!app.state().panels});
    if (ImGui::MenuItem("Outline, axes, step", nullptr, app.state().annotations))
      app.push(cmd::ShowAnnotations{!app.state().annotations});
    if (ImGui::MenuItem("LOD cut", "L", app.state().show_cut))
      app.push(cmd::ShowCut{!app.state().show_cut});
    bool persp = app.state().camera.projection == tsp::Projection::perspective;
    if (ImGui::MenuItem("Perspective", "P", &persp))
      app.push(cmd::SetProjection{persp});
    if (ImGui::MenuItem("Reset camera", "R")) app.push(cmd::ResetCamera{});
    if (bool on = app.help_shown(); ImGui::MenuItem("Controls", "F1", &on))
      app.push(cmd::ShowHelp{on});
    ImGui::EndMenu();
  }
  // On the right: the recording and the frame rate, always in sight.
  char right[128];
  const double ms = app.history.empty() ? 0.0 : app.history.back().ms;
  if (app.recording())
    std::snprintf(right, sizeof right, "REC %.1f s   %.1f ms", app.recorded_seconds(), ms);
  else
    std::snprintf(right, sizeof right, "%.1f ms", ms);
  const float tw = ImGui::CalcTextSize(right).x;
  ImGui::SetCursorPosX(ImGui::GetWindowWidth() - tw - 12);
  if (app.recording())
    ImGui::TextColored(ImVec4(1.f, 0.35f, 0.3f, 1.f), "%s", right);
  else
    ImGui::TextDisabled("%s", right);
  ImGui::EndMainMenuBar();
}

// Every dialog is placed in the middle of the volume's view (docked: left of the side panel,
// which the 560 px wide Open dialog overlapped by 8 px at 1280x800), as wide as `width` or the
// view allows.
void place_dialog(const PlayerApp& app, float width) {
  const WindowRect& v = app.layout.view;
  // (Kept in the middle as it grows: an error line under File > Open's path.)
  const float w = std::min(width, std::max(240.f, float(v.w) - 16.f));
  ImGui::SetNextWindowPos(ImVec2(v.x + v.w * 0.5f, v.y + v.h * 0.5f), ImGuiCond_Always,
                          ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(ImVec2(w, 0), ImGuiCond_Always);  // (its height fits what it holds)
}

// File > Open's outcome, before the dialog is drawn: an open pressed last frame closes the
// dialog when it succeeded or started a build, else leaves its error in it; a build's failure
// opens the dialog again with the path and the error.
void open_outcome(PlayerApp& app, MenuState& s) {
  const PlayerApp::OpenOutcome& o = app.open_outcome();
  const bool ended = o.ended != s.outcome_seen;
  if (s.reopen_on_failure && ended) {
    s.reopen_on_failure = false;
    s.outcome_seen = o.ended;
    if (!o.error.empty()) {
      s.open_error = o.error;
      ImGui::OpenPopup(kOpenPopup);
      s.focus_path = true;
      app.trace("open dialog error: " + s.open_error);
    }
    return;
  }
  if (!s.awaiting) return;
  s.awaiting = false;
  s.outcome_seen = o.ended;
  std::string error = ended ? o.error : "";
  if (!ended && app.open_job()) {  // a build runs: its progress dialog takes over
    s.reopen_on_failure = true;
  } else if (!ended && app.status_is_error()) {  // refused before it began
    error = app.status_line();
  }
  if (error.empty()) {
    s.close_open = true;
    return;
  }
  s.open_error = error;
  s.focus_path = true;
  app.trace("open dialog error: " + s.open_error);
}

// The failed open, in red as the status area's errors, under the path (none: nothing drawn).
void open_error_line(const MenuState& s) {
  if (s.open_error.empty()) return;
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.f, 0.45f, 0.4f, 1.f));
  ImGui::TextWrapped("%s", s.open_error.c_str());
  ImGui::PopStyleColor();
  note_wrapped(s.open_error.c_str());
}

// Open pressed: the dialog stays open until the open ends (a failure is shown in it, the path
// kept to fix).
void start_open(PlayerApp& app, MenuState& s) {
  app.trace(std::string("open dialog opens ") + s.open_path);
  app.push(cmd::OpenInput{s.open_path, s.field, s.build_options});
  s.awaiting = true;
  s.outcome_seen = app.open_outcome().ended;
  s.open_error.clear();
}

// The dialog's build options field (a raw series' grid, a mesh's resolution, …); true on Enter.
bool build_options_field(MenuState& s) {
  // The field as wide as the row leaves beside its whole label.
  ImGui::SetNextItemWidth(-(ImGui::CalcTextSize("build options").x + ImGui::GetStyle().ItemInnerSpacing.x + 1));
  // The hint the field has room for (the examples ran past it; all of them in the tooltip).
  const float field_w = ImGui::CalcItemWidth();
  const char* hint = "e.g. --resolution 128 | --raw-dims 64,64,64 --raw-type f32";
  if (ImGui::CalcTextSize(hint).x + 2 * ImGui::GetStyle().FramePadding.x > field_w)
    hint = "e.g. --resolution 128";
  ImGui::InputTextWithHint("build options", hint, s.build_options, sizeof s.build_options);
  note_item("build options");
  if (!s.build_options[0]) note_hint(hint, field_w);
  const bool enter = entered();
  if (ImGui::IsItemHovered())
    tooltip("As on play's command line: a raw series' grid and type (--raw-dims 64,64,64 "
            "--raw-type f32), a mesh's resolution or voxel size (--resolution 128), a PLOT3D "
            "solution's grid (--xyz grid.xyz); tspplay play --help");
  return enter;
}

void open_dialog(PlayerApp& app) {
  MenuState& s = state();
  if (s.want_open) {
    s.want_open = false;
    std::error_code ec;
    fs::path start = app.open_folder();
    if (start.empty() || !fs::is_directory(start, ec)) start = fs::current_path(ec);
    s.listing.read(fs::absolute(start, ec));
    copy(s.open_path, sizeof s.open_path, s.listing.dir.string() + "/");
    ImGui::OpenPopup(kOpenPopup);
    s.focus_path = true;
    s.traced_list.clear();
    s.open_error.clear();
    app.trace("open dialog");
  }
  open_outcome(app, s);
  place_dialog(app, 560);
  if (!ImGui::BeginPopupModal(kOpenPopup, nullptr)) return;
  note_window(kOpenPopup);
  const char* intro = "A .tsp file, or any input build reads (HDF5, NetCDF, VTK, raw patterns): "
                      "it is built into the cache folder first.";
  ImGui::TextWrapped("%s", intro);
  note_wrapped(intro);
  ImGui::TextDisabled("%s", s.listing.dir.string().c_str());
  bool open_now = false;
  // (The list gives up height in a short window: the buttons under it stay in sight.)
  const float list_h = std::clamp(float(app.layout.view.h) - 320.f, 60.f, kBrowserHeight);
  ImGui::BeginChild("##files", ImVec2(0, list_h), true);
  {  // where the list's rows are, for tests that click them (--trace; once per change)
    char where[96];
    std::snprintf(where, sizeof where, "open list %.0f %.0f %.0f", ImGui::GetCursorScreenPos().x,
                  ImGui::GetCursorScreenPos().y, ImGui::GetTextLineHeightWithSpacing());
    if (s.traced_list != where) app.trace(s.traced_list = where);
  }
  // A double-click's second click lands on the folder it entered with the first: not a click on
  // that folder's entry under the mouse (which went down two levels, or opened a file there).
  const ImGuiIO& io = ImGui::GetIO();
  if (io.MouseClicked[0] && io.MouseClickedCount[0] == 1) s.clicked_into = false;
  const bool later_click = s.clicked_into && io.MouseClickedLastCount[0] >= 2;
  auto go = [&s, &app](const fs::path& dir) {
    s.listing.read(dir);
    copy(s.open_path, sizeof s.open_path, s.listing.dir.string() + "/");
    s.clicked_into = true;
    app.trace("open folder " + s.listing.dir.string());
  };
  if (ImGui::Selectable("../") && !later_click) go(s.listing.dir.parent_path());
  if (!s.listing.error.empty()) ImGui::TextColored(ImVec4(1, 0.5f, 0.4f, 1), "%s", s.listing.error.c_str());
  const auto entries = s.listing.entries;  // (a click may re-read the listing)
  for (const auto& [name, is_dir] : entries) {
    if (!is_dir && !s.all_files && !tspgl::has_input_extension(name)) continue;
    const fs::path full = s.listing.dir / name;
    if (ImGui::Selectable((name + (is_dir ? "/" : "")).c_str(), full.string() == s.open_path,
                          ImGuiSelectableFlags_AllowDoubleClick)) {
      if (later_click) {
      } else if (is_dir) {
        go(full);
      } else {
        copy(s.open_path, sizeof s.open_path, full.string());
        open_now = ImGui::IsMouseDoubleClicked(0);
      }
    }
  }
  ImGui::EndChild();
  // (The extensions in its tooltip: in the combo they ran past its right edge, issue 47.)
  int shown = s.all_files ? 1 : 0;
  const char* kinds[] = {"Inputs play reads", "All files"};
  const float arrow = ImGui::GetFrameHeight();
  ImGui::SetNextItemWidth(ImGui::CalcTextSize(kinds[0]).x + 2 * ImGui::GetStyle().FramePadding.x +
                          arrow + 8);
  if (ImGui::Combo("##kinds", &shown, kinds, 2)) s.all_files = shown == 1;
  note_item(kinds[shown], true, arrow);
  if (ImGui::IsItemHovered())
    tooltip(".tsp .h5 .nc .vti .vtu .vts .vtm .pvd .series .q .raw, and the folders that hold them");
  ImGui::SetNextItemWidth(-60);
  // A folder typed (or pasted) into the path is shown in the list above. The field has the keys
  // when the dialog opens (type or paste a path at once; Ctrl+A selects it all).
  if (s.focus_path) {
    ImGui::SetKeyboardFocusHere();
    s.focus_path = false;
  }
  const bool changed = ImGui::InputText("path", s.open_path, sizeof s.open_path);
  note_item("path");
  if (ImGui::IsItemActivated()) app.trace("open path field active");
  bool enter = entered();  // Enter in a field opens the path (a folder's list is shown already)
  if (changed) {
    app.trace(std::string("open path ") + s.open_path);
    std::error_code ec;
    const fs::path typed = fs::weakly_canonical(fs::path(s.open_path), ec);
    if (!ec && fs::is_directory(typed, ec) && typed != fs::weakly_canonical(s.listing.dir, ec))
      s.listing.read(typed);
  }
  open_error_line(s);
  ImGui::SetNextItemWidth(200);
  ImGui::InputText("field (inputs with several)", s.field, sizeof s.field);
  note_item("field (inputs with several)");
  enter = entered() || enter;
  enter = build_options_field(s) || enter;
  std::error_code ec;
  if (enter && fs::is_directory(fs::path(s.open_path), ec)) enter = false;  // its list is shown
  const bool open_clicked = ImGui::Button("Open");
  note_item("Open", true);
  if ((open_clicked || open_now || enter) && !s.awaiting) start_open(app, s);
  ImGui::SameLine();
  const bool cancel = ImGui::Button("Cancel");
  note_item("Cancel", true);
  if (cancel || escape_closes() || take_close()) {
    app.trace("open dialog closed");
    s.awaiting = false;
    ImGui::CloseCurrentPopup();
  } else if (s.close_open) {
    ImGui::CloseCurrentPopup();
  }
  s.close_open = false;
  ImGui::EndPopup();
}

// A one-path dialog (save TF as, record): returns true when OK was pressed.
bool path_dialog(const PlayerApp& app, const char* title, bool& want, char* path, std::size_t size,
                 const char* what) {
  if (want) {
    want = false;
    ImGui::OpenPopup(title);
  }
  place_dialog(app, 480);
  if (!ImGui::BeginPopupModal(title, nullptr)) return false;
  note_window(title);
  ImGui::TextWrapped("%s", what);  // (wrapped: the record dialog's used to run off its right edge)
  note_wrapped(what);
  ImGui::SetNextItemWidth(-1);
  // The path field takes the keys as the dialog opens (as Open's does): type, or Enter for OK.
  if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
  ImGui::InputText("##path", path, size);
  const bool enter = entered();
  bool ok = false;
  const bool ok_clicked = ImGui::Button("OK");
  note_item("OK", true);
  if (ok_clicked || enter) {
    ok = true;
    ImGui::CloseCurrentPopup();
  }
  ImGui::SameLine();
  const bool cancel = ImGui::Button("Cancel");
  note_item("Cancel", true);
  if (cancel || escape_closes() || take_close()) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
  return ok;
}

// While a File > Open input builds: its progress, and a way out.
void progress_dialog(PlayerApp& app) {
  OpenJob* job = app.open_job();
  if (job && !ImGui::IsPopupOpen(kProgressPopup)) ImGui::OpenPopup(kProgressPopup);
  place_dialog(app, 480);
  if (!ImGui::BeginPopupModal(kProgressPopup, nullptr)) return;
  if (!job) {
    ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
    return;
  }
  const OpenJob::Progress p = job->progress();
  ImGui::TextWrapped("%s", p.line.empty() ? ("opening " + job->input()).c_str() : p.line.c_str());
  const double total = double(p.total), done = double(p.done);
  ImGui::ProgressBar(total > 0 ? float(done / total) : 0.f, ImVec2(-1, 0),
                     p.phase.empty() ? "starting" : p.phase.c_str());
  if (ImGui::Button(job->cancelled() ? "cancelling ..." : "Cancel")) app.cancel_open();
  ImGui::EndPopup();
}

}  // namespace

void show_dialog(const std::string& which) {
  MenuState& s = state();
  s.want_open = s.want_open || which == "open";
  s.want_tf = s.want_tf || which == "save-tf";
  s.want_record = s.want_record || which == "record";
  s.want_session = s.want_session || which == "save-session";
  s.want_close = which == "close";
}

void menu_and_dialogs(PlayerApp& app) {
  MenuState& s = state();
  menu_bar(app);
  open_dialog(app);
  if (s.want_tf) copy(s.tf_path, sizeof s.tf_path, tf_file_path());
  if (path_dialog(app, kTfPopup, s.want_tf, s.tf_path, sizeof s.tf_path,
                  "Our transfer-function JSON (docs/transfer-functions.md):"))
    app.save_tf_as(s.tf_path);
  // A new recording never replaces an earlier movie unless its name is typed: the dialog offers
  // the first free name, NAME_FIELD.mp4 as S names its pictures (NAME_FIELD-2.mp4, …; .gif
  // when the last was one).
  if (s.want_record) {
    const bool gif = std::string_view(s.movie_path).ends_with(".gif");
    copy(s.movie_path, sizeof s.movie_path,
         tsp::unused_path((fs::path(app.export_folder()) / (app.export_stem() + (gif ? ".gif" : ".mp4")))
                              .string()));
  }
  if (path_dialog(app, kRecordPopup, s.want_record, s.movie_path, sizeof s.movie_path,
                  "The volume as shown, with its annotations, in real time (.mp4 or .gif); "
                  "File > Stop recording writes it:"))
    app.push(cmd::StartRecording{s.movie_path});
  if (s.want_session) {  // named after the dataset, beside it or where the last one went
    copy(s.session_path, sizeof s.session_path, app.session_offer());
    app.trace(std::string("save session dialog offers ") + s.session_path);
  }
  if (path_dialog(app, kSessionPopup, s.want_session, s.session_path, sizeof s.session_path,
                  "The transfer function, view, probes, surface, axis scale, speed and panels, "
                  "for tspplay play --session FILE:"))
    app.push(cmd::SaveSession{s.session_path});
  progress_dialog(app);
  s.want_close = false;  // (no dialog was open to take it)
}

}  // namespace tspplayer
