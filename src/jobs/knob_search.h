// Table 4's search over every quality knob (docs/bench.md): for each target mean ΔE against the
// full-quality picture, the configurations that stay within it — the non-TSP baseline over
// compositing × slice spacing, the TSP renderer over compositing × spacing × tolerance rule ×
// tolerance (the fastest tolerance per cell within the target, from zero and the bisection of
// tolerance_search.h) — fastest first by the probe's own frame time. Pure logic over a probe
// callback, so it is tested without GL.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "jobs/tolerance_search.h"
#include "render/frame_report.h"
#include "tsp/metric/metric.h"

namespace tspgl {

/// Which tolerances a searched tolerance τ sets (TSP).
enum class ToleranceRule {
  equal,     ///< spatial = temporal = τ
  temporal,  ///< temporal τ, spatial 0: steps merge, nothing is drawn flat
  spatial,   ///< spatial τ, temporal 0
};
/// "equal", "temporal" or "spatial".
const char* to_string(ToleranceRule r);
/// Parses one of to_string's words; throws tsp::UsageError naming option and the text.
ToleranceRule parse_tolerance_rule(const std::string& text, const std::string& option);

/// One configuration of the quality knobs.
struct Knobs {
  bool baseline = false;                        ///< the non-TSP renderer (tol unused)
  Compositing compositing = Compositing::rays;  ///< how textured boxes are drawn
  double spacing = kDefaultSliceSpacing;        ///< slice spacing in voxels
  double tol = 0;                               ///< the tolerance τ (TSP), set per rule
  ToleranceRule rule = ToleranceRule::equal;    ///< which tolerances τ sets
  bool preintegrated = false;                   ///< pre-integrated TF lookup
  int lod_level = 0;  ///< TSP: an LOD level drawn everywhere (render --lod K; 0: full resolution)
  double sampling_tol = 0;  ///< TSP, rays: adaptive sampling's tolerance (0: off)
  double render_scale = 1;  ///< rays every 1/render_scale pixels (RenderSettings::render_scale)
  /// Every knob equal.
  bool operator==(const Knobs&) const = default;
};

/// Sets settings' compositing, spacing, tolerances (k.tol under k.rule),
/// pre-integration and adaptive sampling from k (k.baseline is the caller's to honour). Never throws.
void apply(const Knobs& k, RenderSettings& settings);

/// The exact `tspplay render` options that draw k (with --metric for the TSP renderer), e.g.
/// "--compositing rays --spacing 2 --metric approximate --spatial-tol 0.01 --temporal-tol 0.01"
/// (and "--preintegrated on", "--sampling-tol X", "--render-scale S" when set).
/// Numbers are written with 17 significant digits, so they parse back to the same doubles.
std::string render_options(const Knobs& k, tsp::Metric metric);

/// What one probe of a configuration measured.
struct ProbeResult {
  double mean_de = 0;  ///< mean ΔE against the full-quality pictures
  double ms = 0;       ///< the probe's median frame time (for ranking only)
};

/// Renders the probe steps under k and compares them (may throw; the search passes it on).
using ProbeKnobs = std::function<ProbeResult(const Knobs& k)>;

/// A configuration and what its probe measured.
struct KnobCandidate {
  Knobs knobs;
  ProbeResult probe;
};

/// The knob values tried.
struct KnobGrid {
  std::vector<Compositing> compositings{Compositing::slices, Compositing::boxes,
                                        Compositing::rays};
  std::vector<double> spacings{0.5, 1, 1.5, 2, 3, 4};
  /// Render scales tried with every spacing (VTK's image sample distance is 1 / scale).
  std::vector<double> render_scales{1};
  std::vector<bool> preintegration{false};  ///< TF lookups tried (point, pre-integrated)
  std::vector<int> lod_levels{0};  ///< TSP only: LOD levels drawn everywhere (0: full resolution)
  /// TSP only: adaptive sampling tolerances (0: off), tried with rays and the point lookup.
  std::vector<double> sampling_tols{0};
  /// TSP only: the tolerance rules searched, each over every other cell.
  std::vector<ToleranceRule> tolerance_rules{ToleranceRule::equal};
};

/// Every cell of grid (pre-integration × compositing × spacing, and for the TSP renderer × LOD
/// level × sampling tolerance — a positive one with rays and the point lookup only — × tolerance
/// rule; tol 0),
/// baseline as given.
std::vector<Knobs> grid_cells(const KnobGrid& grid, bool baseline);

/// For each target: the baseline configurations of grid (every compositing × spacing, each
/// probed once) whose mean ΔE is ≤ the target, fastest probe first. Throws what probe throws.
std::vector<std::vector<KnobCandidate>> search_baseline_knobs(const ProbeKnobs& probe,
                                                              const KnobGrid& grid,
                                                              const std::vector<double>& targets);

/// For each target: per cell of grid (tolerance rules included), the fastest TSP configuration
/// probed within the target — zero tolerance (probed once for all rules, offered by the first
/// rule's cells) and the tolerances search_tolerances tries (span, iterations) on its way to the
/// largest one —; fastest probe first. Throws what probe throws.
std::vector<std::vector<KnobCandidate>> search_tsp_knobs(const ProbeKnobs& probe,
                                                         const KnobGrid& grid,
                                                         const ErrorSpan& span,
                                                         const std::vector<double>& targets,
                                                         int iterations);

}  // namespace tspgl
