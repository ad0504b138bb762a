// The player's commands: one small struct per thing a user can ask for, with named fields. A
// script line, a key and a panel widget make the same Command; validate() checks it whoever made
// it and apply() (player_commands.cpp) carries it out — the one path by which the player's state
// changes. GL-, GLFW- and ImGui-free (library tspscript), so tests build them directly.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <variant>

#include "tsp/clip/probe.h"
#include "tsp/metric/metric.h"
#include "tsp/metric/transfer_function.h"

namespace tspplayer {

/// Longest wait-seconds.
inline constexpr double kMaxWaitSeconds = 600;
/// Largest target-fps.
inline constexpr double kMaxTargetFps = 240;
/// Playback speeds accepted, steps per second (the panel's slider spans them too).
inline constexpr double kMinSpeed = 0.25, kMaxSpeed = 60;
/// How long `wait-file` waits when its line names no timeout, seconds.
inline constexpr double kDefaultWaitFileSeconds = 120;

struct PlayerState;

/// The commands, one struct each (script line in docs/player.md "Scripts").
namespace cmd {
/// `step K`: go to step K (pauses playback).
struct GoToStep { int step = 0; bool operator==(const GoToStep&) const = default; };
/// `play`: start playback.
struct Play { bool operator==(const Play&) const = default; };
/// `pause`: stop playback.
struct Pause { bool operator==(const Pause&) const = default; };
/// `speed S`: playback speed in steps per second.
struct SetSpeed { double steps_per_s = 5; bool operator==(const SetSpeed&) const = default; };
/// `loop on|off`: playback wraps at the end.
struct SetLoop { bool on = true; bool operator==(const SetLoop&) const = default; };
/// `tf FILE|preset:NAME`: load a transfer function, placed over the data as play's --tf is (the
/// TF editor's colour map combo and load button: over the present map's range instead).
struct LoadTf {
  std::string arg;                  ///< a TF file or preset:NAME
  bool over_present_range = false;  ///< placed over the present map's range, not the data's
  bool operator==(const LoadTf&) const = default;
};
/// `tf-range data|histogram|step|visible|LO:HI`: the TF as it is, stretched over that range.
struct StretchTf { std::string range; bool operator==(const StretchTf&) const = default; };
/// `tolerance S T`: spatial and temporal error tolerances. `settled` false: a slider still
/// dragging (frames follow at once; textures are dropped and the readout measured once it
/// settles).
struct SetTolerance {
  double spatial = 0, temporal = 0;  ///< the tolerances (>= 0, finite)
  bool settled = true;               ///< see above
  bool operator==(const SetTolerance&) const = default;
};
/// A row of render/settings_table.h (`spacing 0.5`, `compositing rays`, ...) set from text.
struct SetSetting {
  std::string name, value;  ///< the row's name and the text it parses
  bool operator==(const SetSetting&) const = default;
};
/// `metric NAME`: the error metric frames read.
struct SetMetric {
  tsp::Metric metric = tsp::Metric::approximate;  ///< the metric
  bool operator==(const SetMetric&) const = default;
};
/// `cache on|off`: the texture cache (the settings panel also sets its budget).
struct SetCache {
  bool on = true;        ///< the cache
  double budget_mb = -1;  ///< the texture budget in MiB (< 0: as it is)
  bool operator==(const SetCache&) const = default;
};
/// `prefetch on|off`: background brick prefetch while playing.
struct SetPrefetch { bool on = true; bool operator==(const SetPrefetch&) const = default; };
/// `view AZ EL`: the camera's direction in degrees.
struct SetView {
  double azimuth_deg = 0, elevation_deg = 0;  ///< elevation in (-90, 90)
  bool operator==(const SetView&) const = default;
};
/// `zoom F`: the camera's zoom (> 0).
struct SetZoom { double zoom = 1; bool operator==(const SetZoom&) const = default; };
/// `projection persp|ortho`.
struct SetProjection { bool perspective = false; bool operator==(const SetProjection&) const = default; };
/// `screenshot PATH` / `screenshot-ui PATH`: save the next complete frame.
struct Screenshot {
  std::string path;     ///< the PNG
  bool with_ui = false; ///< with the UI panels (screenshot-ui)
  bool operator==(const Screenshot&) const = default;
};
/// `wait-frames N`: let N frames pass.
struct WaitFrames { int frames = 0; bool operator==(const WaitFrames&) const = default; };
/// `wait-seconds S`: let S seconds pass (frames keep running).
struct WaitSeconds { double seconds = 0; bool operator==(const WaitSeconds&) const = default; };
/// `quality DE`: the playing quality target, mean ΔE (0: none; tunes once, blocking).
struct SetQuality { double mean_de = 0; bool operator==(const SetQuality&) const = default; };
/// `stats FILE.json`: write the HUD statistics.
struct WriteStats { std::string path; bool operator==(const WriteStats&) const = default; };
/// `lod on|off`: the adaptive LOD cut.
struct SetLod { bool on = true; bool operator==(const SetLod&) const = default; };
/// `target-fps FPS`: held while interacting.
struct SetTargetFps { double fps = 30; bool operator==(const SetTargetFps&) const = default; };
/// `lod-filter error|distance[:K]|fov[:K]`: how the cut is chosen.
struct SetLodFilter { std::string filter; bool operator==(const SetLodFilter&) const = default; };
/// `show-cut on|off` (key L): outline the cut's nodes by level.
struct ShowCut { bool on = false; bool operator==(const ShowCut&) const = default; };
/// `panels on|off` (Tab): the UI panels, or the volume filling the window.
struct ShowPanels { bool on = true; bool operator==(const ShowPanels&) const = default; };
/// `every-step on|off`: playback shows every step, or keeps real time dropping steps.
struct EveryStep { bool on = true; bool operator==(const EveryStep&) const = default; };
/// `log-opacity on|off`: the TF editor's opacity axis.
struct LogOpacity { bool on = false; bool operator==(const LogOpacity&) const = default; };
/// `open PATH [FIELD] [--OPTION VALUE ...]`: play another input (built first if need be).
struct OpenInput {
  std::string path, field;    ///< the input and its field ("": the first)
  std::string build_options;  ///< as on play's command line ("": play's own)
  bool operator==(const OpenInput&) const = default;
};
/// `field NAME`: show another field of the file.
struct ShowField { std::string name; bool operator==(const ShowField&) const = default; };
/// `probe SPEC`: add a clip probe (selected).
struct AddProbe { tsp::Probe probe; bool operator==(const AddProbe&) const = default; };
/// `probe-op intersect|union|subtract`: how the probes combine.
struct SetProbeOp {
  tsp::ProbeOp op = tsp::ProbeOp::intersect;  ///< the combination
  bool operator==(const SetProbeOp&) const = default;
};
/// `probe-surface on|off`: draw the clip surface.
struct ProbeSurface { bool on = true; bool operator==(const ProbeSurface&) const = default; };
/// `probe-clear`: remove every probe.
struct ClearProbes { bool operator==(const ClearProbes&) const = default; };
/// `probe-move N DX DY DZ`: move probe N (1-based) by a physical displacement.
struct MoveProbe {
  int number = 1;                 ///< 1-based
  std::array<double, 3> by{};     ///< physical displacement
  bool operator==(const MoveProbe&) const = default;
};
/// `record PATH.mp4|PATH.gif`: start recording a movie.
struct StartRecording { std::string path; bool operator==(const StartRecording&) const = default; };
/// `record stop`: stop recording and write the movie (waits for the encoder).
struct StopRecording { bool operator==(const StopRecording&) const = default; };
/// `reset-camera` (key R, View > Reset camera, the view panel's button).
struct ResetCamera { bool operator==(const ResetCamera&) const = default; };
/// `playback quality|rate`: with a quality target, keep quality (true) or the rate.
struct KeepQuality { bool on = true; bool operator==(const KeepQuality&) const = default; };
/// `capture DIR|off`: save every frame as drawn ("": off).
struct Capture { std::string dir; bool operator==(const Capture&) const = default; };
/// `quit`: close the player.
struct Quit { bool operator==(const Quit&) const = default; };
/// `save-session PATH`.
struct SaveSession { std::string path; bool operator==(const SaveSession&) const = default; };
/// `scale SX,SY,SZ`: stretch the axes.
struct SetScale {
  std::array<double, 3> factors{1, 1, 1};  ///< each in (0, kMaxScale]
  bool operator==(const SetScale&) const = default;
};
/// `expand on|off`: every section of the panels open, or as they start.
struct ExpandSections { bool on = true; bool operator==(const ExpandSections&) const = default; };
/// Key S, File > Save PNG, the view panel's button: save the volume as NAME_step_NNNN.png.
struct SavePicture { bool operator==(const SavePicture&) const = default; };
/// The view panel's and View menu's checkbox: outline box, axes, step and legend over the volume.
struct ShowAnnotations { bool on = true; bool operator==(const ShowAnnotations&) const = default; };
/// The LOD panel's checkbox: splats (not a smaller target) below the coarsest cut.
struct SplatFallback { bool on = false; bool operator==(const SplatFallback&) const = default; };
/// The probes panel: replace probe `index` (0-based) by `probe` (an edited copy), selecting it.
struct EditProbe {
  int index = 0;     ///< 0-based
  tsp::Probe probe;  ///< its new shape
  bool operator==(const EditProbe&) const = default;
};
/// The probes panel's "remove": probe `index` (0-based) goes.
struct RemoveProbe { int index = 0; bool operator==(const RemoveProbe&) const = default; };
/// `dialog open|save-tf|record|save-session|close`: open a File menu dialog as its menu item
/// does (File > Open, Save transfer function as, Record movie, Save session), or close the one
/// open (as Cancel).
struct ShowDialog { std::string which; bool operator==(const ShowDialog&) const = default; };
/// `tf-point move N VALUE OPACITY`: the TF editor's point N (1-based, by value) to VALUE (in the
/// map's range; kept between its neighbours) at OPACITY, the curve warped with it (a handle's
/// drag, the point list's value and opacity).
struct MoveTfPoint {
  int number = 1;                    ///< 1-based, by increasing value
  double value = 0, opacity = 0;     ///< where it goes; opacity in [0, 1]
  bool operator==(const MoveTfPoint&) const = default;
};
/// `tf-point colour N R G B A`: point N's colour and opacity (the point list's colour picker).
struct ColourTfPoint {
  int number = 1;     ///< 1-based, by increasing value
  tsp::Rgba colour;   ///< each component in [0, 1]
  bool operator==(const ColourTfPoint&) const = default;
};
/// `tf-point add VALUE [OPACITY]`: a point at VALUE (in the map's range) in the map's colour there,
/// at OPACITY or the map's own (a double-click on the editor's canvas, the list's "add point").
struct AddTfPoint {
  double value = 0;               ///< where
  std::optional<double> opacity;  ///< in [0, 1]; nullopt: the map's opacity at value
  bool operator==(const AddTfPoint&) const = default;
};
/// `tf-point remove N`: point N goes (of three or more), the curve straight between its
/// neighbours (a right-click on a handle, the list's "x").
struct RemoveTfPoint { int number = 1; bool operator==(const RemoveTfPoint&) const = default; };
/// `wait-file PATH [TIMEOUT_S]`: the script waits until PATH exists (the window keeps taking
/// events), then until every window event sent before PATH was made is taken and settled (a
/// test's xdotool input); an error after TIMEOUT_S (0 … 600) without it.
struct WaitFile {
  std::string path;                             ///< the file a test makes
  double timeout_s = kDefaultWaitFileSeconds;   ///< how long before the script fails
  bool operator==(const WaitFile&) const = default;
};
/// The probes panel: probe `index` (0-based) becomes the one the gizmo moves (no script line).
struct SelectProbe { int index = 0; bool operator==(const SelectProbe&) const = default; };
/// The help overlay's close box and View > Controls (F1 toggles it as well; no script line).
struct ShowHelp { bool on = true; bool operator==(const ShowHelp&) const = default; };
/// `signal PATH`: writes PATH (atomically; "frame N") when the script reaches it, for a test
/// that waits on it before sending input.
struct Signal { std::string path; bool operator==(const Signal&) const = default; };
}  // namespace cmd

/// One player command (see namespace cmd).
using Command =
    std::variant<cmd::GoToStep, cmd::Play, cmd::Pause, cmd::SetSpeed, cmd::SetLoop, cmd::LoadTf,
                 cmd::StretchTf, cmd::SetTolerance, cmd::SetSetting, cmd::SetMetric,
                 cmd::SetCache, cmd::SetPrefetch, cmd::SetView, cmd::SetZoom,
                 cmd::SetProjection, cmd::Screenshot, cmd::WaitFrames, cmd::WaitSeconds,
                 cmd::SetQuality, cmd::WriteStats, cmd::SetLod, cmd::SetTargetFps,
                 cmd::SetLodFilter, cmd::ShowCut, cmd::ShowPanels, cmd::EveryStep,
                 cmd::LogOpacity, cmd::OpenInput, cmd::ShowField, cmd::AddProbe,
                 cmd::SetProbeOp, cmd::ProbeSurface, cmd::ClearProbes, cmd::MoveProbe,
                 cmd::StartRecording, cmd::StopRecording, cmd::ResetCamera, cmd::KeepQuality,
                 cmd::Capture, cmd::Quit, cmd::SaveSession, cmd::SetScale,
                 cmd::ExpandSections, cmd::SavePicture, cmd::ShowAnnotations,
                 cmd::SplatFallback, cmd::EditProbe, cmd::RemoveProbe, cmd::ShowDialog,
                 cmd::MoveTfPoint, cmd::ColourTfPoint, cmd::AddTfPoint, cmd::RemoveTfPoint,
                 cmd::WaitFile, cmd::Signal, cmd::SelectProbe, cmd::ShowHelp>;

/// True when a script stops after c until frames pass: a screenshot, `wait-frames N` with N > 0,
/// `wait-file` or `wait-seconds S` with S > 0 (a wait of 0 is free: it used to cost a frame, and a script of
/// a million `wait-frames 0` lines ran for 45 minutes). Never throws.
bool waits_for_frames(const Command& c);

/// Checks a command's values (speed, tolerances, view, zoom, waits, targets, render settings)
/// whoever made it — a script line, a key or a panel: the one validation of player commands.
/// Throws tsp::UsageError naming the action and what it accepts.
void validate(const Command& c);

/// The command a key press (a GLFW key code) makes with the player in state s over a file of
/// `steps` steps (Space, arrows, Home, End, S, L, R, Tab, P); nullopt for other keys. Never
/// throws.
std::optional<Command> key_command(int key, const PlayerState& s, int steps);

}  // namespace tspplayer
