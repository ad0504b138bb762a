#include "player/export_names.h"

#include <cctype>
#include <filesystem>

namespace tspplayer {

std::string dataset_name(const std::string& input) {
  static constexpr const char* kExtensions[] = {
      ".series", ".tsp", ".h5",  ".hdf5", ".hdf", ".he5", ".nc", ".nc4", ".vtkhdf", ".vti",
      ".vtu",    ".vts", ".vtm", ".pvd",  ".q",   ".xyz", ".raw"};
  std::string name = std::filesystem::path(input).filename().string();
  for (bool stripped = true; stripped;) {  // (.vtu.series: both)
    stripped = false;
    for (const char* ext : kExtensions) {
      const std::string e = ext;
      if (name.size() <= e.size()) continue;
      bool same = true;
      for (std::size_t k = 0; k < e.size() && same; ++k)
        same = std::tolower(static_cast<unsigned char>(name[name.size() - e.size() + k])) == e[k];
      if (same) {
        name.resize(name.size() - e.size());
        stripped = true;
      }
    }
  }
  return name.empty() ? "tspplay" : name;
}

}  // namespace tspplayer
