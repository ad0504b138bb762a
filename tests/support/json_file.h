// The JSON files the CLI writes (frames.json, report.json, calibration files), read back by the
// tests.
#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>

namespace tsptest {

/// The JSON document in file p; throws nlohmann::json::parse_error when p is missing or not JSON.
nlohmann::json read_json(const std::filesystem::path& p);

/// The frames.json `render` wrote into its output folder dir (read_json).
nlohmann::json frames_json(const std::filesystem::path& dir);

}  // namespace tsptest
