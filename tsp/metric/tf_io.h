// Transfer-function files and presets: our JSON, ParaView colour-map presets, named presets.
// Formats: docs/transfer-functions.md.
#pragma once
#include <string>
#include <vector>

#include "tsp/metric/transfer_function.h"

namespace tsp {

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

/// Names of the built-in presets ("sparse", "filled", "grey").
std::vector<std::string> preset_names();

/// A built-in preset stretched over domain. Throws UsageError for an unknown name (listing the
/// known ones) or an invalid domain.
TransferFunction preset_transfer_function(const std::string& name, ValueRange domain,
                                          int entries = kDefaultTfEntries);

/// The domain a preset is stretched over for data whose values span r: r itself when it is a
/// finite interval with lo < hi; for a constant field (lo = hi) the interval of width
/// max(1, |lo|·1e-3) centred on it, so the constant sits mid-map and still renders; [0, 1]
/// when r is not finite. Never throws.
ValueRange preset_domain(ValueRange r);

/// Resolves a --tf argument: "preset:NAME" gives that preset over preset_domain(default_domain),
/// anything else is a file path. Throws like load_transfer_function / preset_transfer_function.
TransferFunction transfer_function_from_arg(const std::string& arg, ValueRange default_domain,
                                            int entries = kDefaultTfEntries);

}  // namespace tsp
