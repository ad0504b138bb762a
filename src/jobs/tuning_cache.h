// The playback tunings kept on disk (issue 47 item 1): a tuning is stored per file, field, TF,
// metric, settings, view size and camera, so a window reopened on the same data plays at its
// tuned rung at once instead of probing the ladder again. Entries are inputs and outputs like any
// other cache's (docs/robustness.md): read through the input gate, written without following a
// link planted at their name.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "jobs/playback_tuner.h"

namespace tspgl {

/// Version of the tuning cache's entries; another version is never read.
inline constexpr int kTuningCacheVersion = 1;

/// The entry for key (any JSON object naming what the tuning depends on):
/// DIR/tuning/tuning-HASH.json under dir ("": default_calibration_dir()); "" when there is no
/// cache folder or dir is "-". Never throws but bad_alloc.
std::string tuning_cache_path(const nlohmann::json& key, const std::string& dir = "");

/// The rungs stored at path for key, or nullopt when the entry is missing, unreadable (a FIFO,
/// too large), of another key or version, or names a rung the ladder no longer has. Never throws
/// but bad_alloc.
std::optional<std::vector<TunedRung>> read_tuning(const std::string& path,
                                                  const nlohmann::json& key);

/// Stores rungs for key at path, creating its folder; a link at path is replaced, never
/// followed. Throws tsp::IoError.
void write_tuning(const std::string& path, const nlohmann::json& key,
                  const std::vector<TunedRung>& rungs);

}  // namespace tspgl
