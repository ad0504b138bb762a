#include "cli/session_options.h"

#include <cassert>
#include <string>

namespace tspcli {

std::string_view to_string(SessionCommand c) {
  switch (c) {
    case SessionCommand::render: return "render";
    case SessionCommand::play: return "play";
    case SessionCommand::bench: return "bench";
  }
  return "?";
}

// Each row: name, group, help, field, choices, then {taken, value, shown} for render, play and
// bench (in SessionCommand order; {} where the command does not take it).
const std::vector<SessionOptionSpec>& session_options() {
  static const std::vector<SessionOptionSpec> table = {
      {"--field", "Input/output",
       "A file with several fields: the one drawn (first); an input that is not a .tsp: the "
       "field to read, or A,B,C (several, one tree each)",
       &SessionArgs::field, {},
       {{{true, "", ""}, {true, "", ""}, {true, "", ""}}}},
      {"--tf", "Input/output",
       "Transfer function: a JSON file or preset:NAME (preset:auto is built from the data's "
       "histogram); bench takes several, one search each",
       &SessionArgs::tf, {},
       {{{true, "preset:auto", ""}, {true, "preset:auto", ""}, {true, "preset:sparse", ""}}}},
      {"--tf-range", "Input/output",
       "Where the TF sits over the data: auto, data, file, bulk (1st-99th percentile; also "
       "histogram), step (the first step's range), view (what the starting view shows of it; "
       "also visible) or LO:HI",
       &SessionArgs::tf_range, {},
       {{{true, "", "auto"}, {true, "", "auto"}, {}}}},
      {"--size", "Camera",
       "Image (or window) size WxH",
       &SessionArgs::size, {},
       {{{true, "640x480", ""}, {true, "960x720", ""}, {true, "640x480", ""}}}},
      {"--view", "Camera",
       "Azimuth,elevation in degrees",
       &SessionArgs::view, {},
       {{{true, "30,20", ""}, {}, {true, "30,20", ""}}}},
      {"--proportions", "Camera",
       "physical (the file's voxel spacing shapes the view) or samples (cubic voxels)",
       &SessionArgs::proportions, {},
       {{{true, "physical", ""}, {true, "physical", ""}, {}}}},
      {"--scale", "Camera",
       "SX,SY,SZ: stretch each axis by this factor (e.g. 1,1,20 exaggerates height)",
       &SessionArgs::scale, {},
       {{{true, "", ""}, {true, "", ""}, {}}}},
      {"--probe", "Probes",
       "Clip probe in physical coordinates, repeatable: plane:A,B,C,D (keeps A*x+B*y+C*z <= D), "
       "sphere:X,Y,Z,R or box:X,Y,Z,HX,HY,HZ[,AX,AY,AZ] (half sizes, rotation in degrees); the "
       "volume outside their combination is not drawn",
       &SessionArgs::probes, {},
       {{{true, "", ""}, {true, "", ""}, {}}}},
      {"--probe-op", "Probes",
       "How the probes combine: intersect, union or subtract (the first minus the others)",
       &SessionArgs::probe_op, {"intersect", "union", "subtract"},
       {{{true, "intersect", ""}, {true, "intersect", ""}, {}}}},
      {"--probe-surface", "Probes",
       "on: the clip surface drawn opaque, coloured by the data and shaded by its normal; off: "
       "pure clipping",
       &SessionArgs::probe_surface, {"on", "off"},
       {{{true, "off", ""},
         {true, "on", "on, so a probe placed in the window shows what it cuts"},
         {}}}},
      {"--surface-mesh", "Surface",
       "The mesh series the file was built from (any build input: .vtu, .pvd, .vtm.series, "
       "'can_%d.hdf', ...), whose boundary --surface boundary draws",
       &SessionArgs::surface_mesh, {},
       {{{true, "", ""}, {true, "", "the input, when it is a mesh"}, {}}}},
      {"--surface-field", "Surface",
       "The field the surface shows (any of the mesh's, e.g. another than the volume's)",
       &SessionArgs::surface_field, {},
       {{{true, "", "the file's field"}, {true, "", "the file's field"}, {}}}},
      {"--surface-tf", "Surface",
       "Colours of the surface: a TF file or preset:NAME",
       &SessionArgs::surface_tf, {},
       {{{true, "", "preset:cool-to-warm over the surface's values"},
         {true, "", "preset:cool-to-warm over the surface's values"},
         {}}}},
      {"--lod", "LOD",
       "Spatial level of detail: off (full resolution), auto or on (the adaptive cut: holds "
       "--target-fps while frames move, refines to full quality when they stop), K (level K "
       "everywhere; 0 = full; render) or splat:PX (every node one splat of its mean colour, "
       "split while its children project to PX pixels or more; render)",
       &SessionArgs::lod, {},
       {{{true, "", "off, or auto with --target-fps"},
         {true, "auto", "auto: interacting holds --target-fps, idle refines to full quality"},
         {}}}},
      {"--lod-fallback", "LOD",
       "When even the coarsest cut misses the target: scale (a smaller render target) or "
       "splats (a splat cut whose minimum size adapts)",
       &SessionArgs::lod_fallback, {},
       {{{true, "scale", ""}, {true, "scale", ""}, {}}}},
      {"--lod-filter", "LOD",
       "How the cut is chosen: error (the error-driven cut that holds the target), or LaMar's "
       "selection filters distance[:K] (a tile drawn when the eye is more than K times its "
       "diagonal away) and fov[:K] (drawn when it subtends less than half the field of view "
       "over K)",
       &SessionArgs::lod_filter, {},
       {{{true, "error", ""}, {true, "error", ""}, {}}}},
      {"--target-fps", "LOD",
       "Frames per second the adaptive cut holds",
       &SessionArgs::target_fps, {},
       {{{true, "", "off"}, {true, "30", ""}, {}}}},
      {"--quality", "Quality",
       "Mean dE target against the full-quality picture: render draws every frame with the "
       "fastest calibrated knobs that keep it (calibrated once, cached); play keeps it while "
       "playing with a tuned ladder of knobs (paused frames are full quality); 0: off",
       &SessionArgs::quality, {},
       {{{true, "", "off"}, {true, "1", ""}, {}}}},
      {"--texture-budget", "Memory",
       "Textures resident, MiB",
       &SessionArgs::texture_budget_mb, {},
       {{{true, "512", ""}, {true, "512", ""}, {}}}},
      {"--ram-budget", "Memory",
       "Bricks held in RAM, MiB: a file larger than RAM streams through it",
       &SessionArgs::ram_budget_mb, {},
       {{{true, "1024", ""}, {true, "1024", ""}, {}}}},
      {"--gl", "GL",
       "Which GL draws headless: auto (EGL on a GPU when one is found, else OSMesa), egl (EGL, "
       "on Mesa's software device where there is no GPU) or osmesa; a request EGL cannot serve "
       "falls back to OSMesa with a warning",
       &SessionArgs::gl, {},
       {{{true, "auto", ""}, {}, {true, "auto", ""}}}},
      {"--gpu", "GL",
       "EGL device index to draw on",
       &SessionArgs::gpu, {},
       {{{true, "", "TSPPLAY_EGL_DEVICE, else the first GPU"},
         {},
         {true, "", "TSPPLAY_EGL_DEVICE, else the first GPU"}}}},
  };
  return table;
}

const SessionOptionSpec& session_option(std::string_view name) {
  for (const SessionOptionSpec& s : session_options())
    if (s.name == name) return s;
  assert(false && "session_option: no such row");
  return session_options().front();
}

std::string session_help(const SessionOptionSpec& s, SessionCommand command) {
  const SessionDefault& d = s.in(command);
  std::string help(s.help);
  const std::string_view shown = d.shown.empty() ? d.value : d.shown;
  if (!shown.empty()) help += " (default " + std::string(shown) + ")";
  return help;
}

namespace {

// Sets field of a from text as a default (the table's own numbers: no user text here).
void set_default(SessionArgs& a, const SessionField& field, std::string_view text) {
  const std::string t(text);
  if (const auto* s = std::get_if<std::string SessionArgs::*>(&field))
    a.*(*s) = t;
  else if (const auto* v = std::get_if<std::vector<std::string> SessionArgs::*>(&field))
    a.*(*v) = {t};
  else if (const auto* d = std::get_if<double SessionArgs::*>(&field))
    a.*(*d) = std::stod(t);
  else
    a.*std::get<int SessionArgs::*>(field) = std::stoi(t);
}

}  // namespace

SessionArgs session_defaults(SessionCommand command) {
  SessionArgs a;
  for (const SessionOptionSpec& s : session_options()) {
    const SessionDefault& d = s.in(command);
    if (d.taken && !d.value.empty()) set_default(a, s.field, d.value);
  }
  return a;
}

void add_session_options(CLI::App* c, SessionCommand command, SessionArgs& a,
                         std::initializer_list<std::string_view> except) {
  for (const SessionOptionSpec& s : session_options()) {
    if (!s.in(command).taken) continue;
    bool skip = false;
    for (std::string_view e : except) skip |= e == s.name;
    if (skip) continue;
    CLI::Option* o = std::visit(
        [&](auto member) { return add_session_option(c, command, s.name, a.*member); }, s.field);
    if (!s.choices.empty())
      o->check(CLI::IsMember(std::vector<std::string>(s.choices.begin(), s.choices.end())));
  }
}

std::string lod_word(const std::string& text) { return text == "on" ? "auto" : text; }

}  // namespace tspcli
