#include "support/json_file.h"

#include <fstream>

namespace tsptest {

nlohmann::json read_json(const std::filesystem::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

nlohmann::json frames_json(const std::filesystem::path& dir) {
  return read_json(dir / "frames.json");
}

}  // namespace tsptest
