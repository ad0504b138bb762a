// Reader for VTK XML image data: one .vti file, or a time series of them listed by a .pvd
// collection or a .vti.series JSON file.
#pragma once
#include <memory>
#include <string>

#include "tsp/source/volume_source.h"

namespace tsp::io {

/// Opens one .vti file as a 1-step source. options.field names a PointData array (else a
/// CellData array, read as the grid of cells); empty picks the only array, else the
/// PointData "Scalars" array. Throws IoError (missing file) or FormatError naming the file,
/// the field and what was expected versus found (bad XML, unsupported encoding, compressor,
/// type, several components, truncated data, pieces not covering WholeExtent).
std::unique_ptr<VolumeSource> open_vti_source(const std::string& path,
                                              const SourceOptions& options);

/// Opens a .pvd collection (<Collection><DataSet timestep=".." file=".."/>…), steps ordered by
/// timestep, files relative to the .pvd. Every step must have the same grid. Throws like
/// open_vti_source, plus FormatError for several parts per timestep.
std::unique_ptr<VolumeSource> open_pvd_source(const std::string& path,
                                              const SourceOptions& options);

/// Opens a .vti.series JSON file ({"file-series-version":"1.0","files":[{"name","time"}]}),
/// steps ordered by time, files relative to the series file. Throws like open_pvd_source.
std::unique_ptr<VolumeSource> open_vti_series_source(const std::string& path,
                                                     const SourceOptions& options);

/// Opens a printf pattern or glob of .vti files (see expand_file_pattern), one step per file
/// in pattern order. Throws like open_pvd_source, IoError when nothing matches.
std::unique_ptr<VolumeSource> open_vti_pattern_source(const std::string& pattern,
                                                      const SourceOptions& options);

}  // namespace tsp::io
