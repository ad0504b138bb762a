// Transfer-function files and presets: our JSON, ParaView colour-map presets, named presets.
// Formats: docs/transfer-functions.md.
#pragma once
#include <span>
#include <string>
#include <vector>

#include "tsp/metric/histogram_tf.h"
#include "tsp/metric/transfer_function.h"

namespace tsp {

class TspFile;

/// Reads a transfer function from path: our JSON {"range":[lo,hi],"points":[[x,r,g,b,a],...]}
/// or a ParaView colour-map preset (RGBPoints, optional opacity "Points"). Throws IoError when
/// the file cannot be read, FormatError naming the file and the offending key otherwise.
TransferFunction load_transfer_function(const std::string& path, int entries = kDefaultTfEntries);

/// Parses the text of a transfer-function file; origin names it in error messages.
/// Throws FormatError naming origin and the offending key.
TransferFunction parse_transfer_function(const std::string& text, const std::string& origin,
                                         int entries = kDefaultTfEntries);

/// Writes tf in our JSON format, one point per entry centre (via a temporary file renamed at
/// the end). Throws IoError when the file cannot be written.
void save_transfer_function(const TransferFunction& tf, const std::string& path);

/// The preset built from the data's histogram (histogram_transfer_function): the default --tf.
inline constexpr const char* kAutoPreset = "auto";

/// Names of the built-in presets ("auto", "sparse", "filled", "grey", and ParaView's common maps:
/// "viridis", "inferno", "cool-to-warm", "jet", "grayscale", "rainbow-uniform").
std::vector<std::string> preset_names();

/// A built-in preset stretched over domain; "auto" is histogram_transfer_function(*histogram,
/// domain). Throws UsageError for an unknown name (listing the known ones), an invalid domain,
/// or "auto" without a histogram.
TransferFunction preset_transfer_function(const std::string& name, ValueRange domain,
                                          int entries = kDefaultTfEntries,
                                          const ValueHistogram* histogram = nullptr);

/// A .tsp field's value histogram: its /histogram over its value range (a view into file).
ValueHistogram histogram_of(const TspFile& file);

/// The domain a preset is stretched over for data whose values span r: r itself when it is a
/// finite interval with lo < hi; for a constant field (lo = hi) the interval of width
/// max(1, |lo|·1e-3) centred on it, so the constant sits mid-map and still renders; [0, 1]
/// when r is not finite. Never throws.
ValueRange preset_domain(ValueRange r);

/// How --tf-range places a transfer function over the data.
struct TfRangeChoice {
  enum class Mode {
    automatic,  ///< presets over the data; a file's own range, except a normalised [0, 1] map
                ///< (ParaView presets) for data outside [0, 1], which is stretched over the data
    data,       ///< every TF stretched over the data's range
    file,       ///< a file's own range, whatever it is
    histogram,  ///< stretched over where the data is: its 1st to 99th percentile (tf_domain_of)
    step,       ///< stretched over one step's range (render: the first step drawn; the player:
                ///< the step shown when it is chosen)
    visible,    ///< over the range of what the view shows of that step (the app computes it:
                ///< tspgl::visible_value_range; tf_domain_of gives the step's range)
    explicit_range  ///< stretched over `range`
  };
  Mode mode = Mode::automatic;
  ValueRange range;  ///< explicit_range only
};

/// Parses --tf-range "auto", "data", "file", "bulk" (or "histogram"), "step", "view" (or
/// "visible") or "LO:HI" (finite, LO < HI): bulk and view as the player's fit buttons name them.
/// Throws UsageError.
TfRangeChoice parse_tf_range(const std::string& text);

/// Share of the samples left out below and above the histogram range (1 % each side).
inline constexpr double kHistogramTail = 0.01;

/// The values between the kHistogramTail and 1 − kHistogramTail quantiles of a histogram of
/// equal bins over value_range (a .tsp's /histogram), interpolated inside the bins; value_range
/// when the histogram is empty or the quantiles meet. Never throws.
ValueRange histogram_range(std::span<const std::uint64_t> histogram, ValueRange value_range);

/// The data domain a TF is placed over for choice c: histogram_range for Mode::histogram,
/// step_range for Mode::step and Mode::visible (value_range when step_range is not a finite
/// lo < hi), else
/// value_range. Never throws.
ValueRange tf_domain_of(const TfRangeChoice& c, ValueRange value_range,
                        std::span<const std::uint64_t> histogram, ValueRange step_range = {});

/// tf_domain_of for a .tsp's field at step `step` (its value range, histogram and the step's
/// range). Asserts 0 <= step < steps.
ValueRange tf_domain_of(const TfRangeChoice& c, const TspFile& file, int step);

/// tf with its domain moved to `to`: every entry keeps its colour, its position mapped linearly.
/// Throws UsageError on an invalid `to`.
TransferFunction rescaled(const TransferFunction& tf, ValueRange to);

/// A warning when tf's domain misses the data's range (no overlap), else empty; it names `fix`
/// as what stretches the map over the data (the window's "fit to data"). Never throws.
std::string tf_range_warning(const TransferFunction& tf, ValueRange data,
                             const std::string& fix = "--tf-range data");

/// Resolves a --tf argument: "preset:NAME" gives that preset (histogram: the data's, for
/// preset:auto), anything else is a file path; placed over the data (default_domain) as `range`
/// says. Throws like load_transfer_function / preset_transfer_function.
TransferFunction transfer_function_from_arg(const std::string& arg, ValueRange default_domain,
                                            int entries = kDefaultTfEntries,
                                            const TfRangeChoice& range = {},
                                            const ValueHistogram* histogram = nullptr);

}  // namespace tsp
