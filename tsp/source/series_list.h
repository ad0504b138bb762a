// The lists that name a time series' files: ParaView .pvd collections, .series JSON files
// (.vti.series, .vtu.series, .vtm.series) and .vtm multiblock files (their "internal" block, as
// OpenFOAM's foamToVTK writes it). Shared by the image-data and unstructured readers.
#pragma once
#include <string>
#include <vector>

namespace tsp::io {

/// One step of a series: its file (resolved against the list's folder) and time value.
struct StepFile {
  std::string file;
  double time = 0;
};

/// The DataSets of a .pvd collection in file order. Throws IoError (unreadable) or FormatError
/// naming the file and the entry (not XML, not a Collection, no file or a non-numeric timestep).
std::vector<StepFile> read_pvd(const std::string& path);

/// The files of a .series JSON file in file order. Throws like read_pvd.
std::vector<StepFile> read_file_series(const std::string& path);

/// Sorts steps by time and rejects an empty list or two steps at one time (several parts per
/// step). Throws FormatError naming `list`.
void order_steps(const std::string& list, std::vector<StepFile>& steps);

/// The .vtu a .vtm multiblock file names for its volume: the DataSet called "internal" (at any
/// depth), else the only .vtu DataSet. Throws FormatError naming the file and the blocks found,
/// IoError when the .vtm or the block is not a regular file (a FIFO, a device, missing).
std::string vtm_volume_block(const std::string& path);

/// True when s ends with suffix, ignoring ASCII case (".VTU" is ".vtu"). Never throws.
bool has_suffix(const std::string& s, const std::string& suffix);

/// name resolved against the folder of list_file (absolute names stay). Never throws.
std::string resolve_relative(const std::string& list_file, const std::string& name);

}  // namespace tsp::io
