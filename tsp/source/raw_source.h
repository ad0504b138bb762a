// Reader for series of raw binary volumes, one file per time step.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "tsp/source/volume_source.h"

namespace tsp::io {

/// True when input is a file pattern: a printf index pattern ("u_%04d.raw") or a glob
/// ('*', '?' or '['). Never throws.
bool is_file_pattern(const std::string& input);

/// Expands a raw-series pattern to its files in time order. A printf pattern (one %d with
/// optional 0 flag and width; "%%" is a literal %) is tried from index 0, or from 1 when 0 is
/// missing, upward until the first missing index; a glob is matched and sorted in natural
/// (numeric-aware) order. Any other input names one file. Throws IoError naming the pattern
/// when nothing matches, UsageError for a malformed printf pattern.
std::vector<std::string> expand_file_pattern(const std::string& pattern);

/// Opens a raw series: options.raw_dims (required), raw_type, raw_big_endian; x fastest.
/// Every file must hold exactly X·Y·Z·sizeof(type) bytes. Throws UsageError (no or bad
/// dims), IoError (no file matched, unreadable file) or FormatError (wrong file size).
std::unique_ptr<VolumeSource> open_raw_source(const std::string& input,
                                              const SourceOptions& options);

}  // namespace tsp::io
