#include "jobs/tuning_cache.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "jobs/cache_key.h"
#include "jobs/calibration.h"
#include "tsp/core/error.h"
#include "tsp/core/input_file.h"
#include "tsp/core/json_read.h"
#include "tsp/core/json_text.h"
#include "tsp/core/temp_output.h"

namespace tspgl {

namespace fs = std::filesystem;

namespace {

// Largest entry read (a real one is a few hundred bytes: one line per rung).
constexpr std::int64_t kMaxTuningBytes = std::int64_t(1) << 20;

}  // namespace

std::string tuning_cache_path(const nlohmann::json& key, const std::string& dir) {
  const std::string root = dir.empty() ? default_calibration_dir() : dir;
  if (root.empty() || root == "-") return "";
  return (fs::path(root) / "tuning" / ("tuning-" + key_hash(tsp::json_text(key)) + ".json"))
      .string();
}

std::optional<std::vector<TunedRung>> read_tuning(const std::string& path,
                                                  const nlohmann::json& key) {
  std::error_code ec;
  if (path.empty() || !fs::exists(fs::symlink_status(path, ec))) return std::nullopt;
  try {
    const nlohmann::json j =
        tsp::parse_json(tsp::read_input_file(path, "tuning cache", kMaxTuningBytes), path);
    if (!j.is_object() || j.value("version", 0) != kTuningCacheVersion || j.value("key", nlohmann::json()) != key)
      return std::nullopt;
    std::vector<TunedRung> rungs;
    for (const nlohmann::json& r : j.at("rungs")) {
      const std::string name = r.at("name").get<std::string>();
      TunedRung t;
      bool known = false;
      for (const Rung& ladder : playback_rungs())
        if (name == ladder.name) {
          t.rung = ladder;
          known = true;
        }
      if (!known) return std::nullopt;
      t.mean_de = r.at("mean_de").get<double>();
      t.max_step_de = r.at("max_step_de").get<double>();
      t.ms = r.at("ms").get<double>();
      if (!(t.mean_de >= 0) || !(t.max_step_de >= 0) || !(t.ms >= 0)) return std::nullopt;
      rungs.push_back(t);
    }
    if (rungs.size() != playback_rungs().size()) return std::nullopt;
    return rungs;
  } catch (const std::exception&) {
    return std::nullopt;  // corrupt, foreign or unreadable: tuned again
  }
}

void write_tuning(const std::string& path, const nlohmann::json& key,
                  const std::vector<TunedRung>& rungs) {
  nlohmann::json list = nlohmann::json::array();
  for (const TunedRung& t : rungs)
    list.push_back({{"name", t.rung.name},
                    {"mean_de", t.mean_de},
                    {"max_step_de", t.max_step_de},
                    {"ms", t.ms}});
  const nlohmann::json j = {{"version", kTuningCacheVersion}, {"key", key}, {"rungs", list}};
  std::error_code ec;
  fs::create_directories(fs::path(path).parent_path(), ec);
  if (ec)
    throw tsp::IoError(fs::path(path).parent_path().string() +
                       ": cannot create the tuning cache folder: " + ec.message());
  tsp::write_file_atomically(path, tsp::json_text(j, 1) + "\n", tsp::OutputLinks::replace);
}

}  // namespace tspgl
