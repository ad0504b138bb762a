#include "cli/session_options.h"

#include <cassert>

namespace tspcli {

const std::vector<SessionOptionSpec>& session_options() {
  static const std::vector<SessionOptionSpec> table = {
      {"--field", "Input/output",
       "A file with several fields: the one drawn (first); an input that is not a .tsp: the "
       "field to read, or A,B,C (several, one tree each)"},
      {"--tf", "Input/output",
       "Transfer function: a JSON file or preset:NAME (preset:auto is built from the data's "
       "histogram); bench takes several, one search each"},
      {"--tf-range", "Input/output",
       "Where the TF sits over the data: auto, data, file, histogram (1st-99th percentile), step "
       "(the first step's range), visible (what the starting view shows of it) or LO:HI"},
      {"--size", "Camera", "Image (or window) size WxH"},
      {"--view", "Camera", "Azimuth,elevation in degrees"},
      {"--proportions", "Camera",
       "physical (the file's voxel spacing shapes the view) or samples (cubic voxels)"},
      {"--scale", "Camera",
       "SX,SY,SZ: stretch each axis by this factor (e.g. 1,1,20 exaggerates height)"},
      {"--probe", "Probes",
       "Clip probe in physical coordinates, repeatable: plane:A,B,C,D (keeps A*x+B*y+C*z <= D), "
       "sphere:X,Y,Z,R or box:X,Y,Z,HX,HY,HZ[,AX,AY,AZ] (half sizes, rotation in degrees); the "
       "volume outside their combination is not drawn"},
      {"--probe-op", "Probes",
       "How the probes combine: intersect, union or subtract (the first minus the others)"},
      {"--probe-surface", "Probes",
       "on: the clip surface drawn opaque, coloured by the data and shaded by its normal; off: "
       "pure clipping"},
      {"--surface-mesh", "Surface",
       "The mesh series the file was built from (any build input: .vtu, .pvd, .vtm.series, "
       "'can_%d.hdf', ...), whose boundary --surface boundary draws"},
      {"--surface-field", "Surface",
       "The field the surface shows (any of the mesh's, e.g. another than the volume's)"},
      {"--surface-tf", "Surface",
       "Colours of the surface: a TF file or preset:NAME (preset:cool-to-warm over the "
       "surface's values)"},
      {"--lod", "LOD",
       "Spatial level of detail: off (full resolution), auto or on (the adaptive cut: holds "
       "--target-fps while frames move, refines to full quality when they stop), K (level K "
       "everywhere; 0 = full; render) or splat:PX (every node one splat of its mean colour, "
       "split while its children project to PX pixels or more; render)"},
      {"--lod-fallback", "LOD",
       "When even the coarsest cut misses the target: scale (a smaller render target) or "
       "splats (a splat cut whose minimum size adapts)"},
      {"--lod-filter", "LOD",
       "How the cut is chosen: error (the error-driven cut that holds the target), or LaMar's "
       "selection filters distance[:K] (a tile drawn when the eye is more than K times its "
       "diagonal away) and fov[:K] (drawn when it subtends less than half the field of view "
       "over K)"},
      {"--target-fps", "LOD", "Frames per second the adaptive cut holds"},
      {"--quality", "Quality",
       "Mean dE target against the full-quality picture: render draws every frame with the "
       "fastest calibrated knobs that keep it (calibrated once, cached); play keeps it while "
       "playing with a tuned ladder of knobs (paused frames are full quality); 0: off"},
      {"--texture-budget", "Memory", "Textures resident, MiB"},
      {"--ram-budget", "Memory",
       "Bricks held in RAM, MiB: a file larger than RAM streams through it"},
      {"--gl", "GL",
       "Which GL draws headless: auto (EGL on a GPU when one is found, else OSMesa), egl (EGL, "
       "on Mesa's software device where there is no GPU) or osmesa; a request EGL cannot serve "
       "falls back to OSMesa with a warning"},
      {"--gpu", "GL", "EGL device index to draw on (default: TSPPLAY_EGL_DEVICE, else the first GPU)"},
  };
  return table;
}

const SessionOptionSpec& session_option(std::string_view name) {
  for (const SessionOptionSpec& s : session_options())
    if (s.name == name) return s;
  assert(false && "session_option: no such row");
  return session_options().front();
}

std::string lod_word(const std::string& text) { return text == "on" ? "auto" : text; }

}  // namespace tspcli
