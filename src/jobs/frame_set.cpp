#include "jobs/frame_set.h"

#include <algorithm>
#include <cassert>
#include <cstdio>

#include "tsp/core/error.h"

namespace tspgl {

namespace fs = std::filesystem;
using nlohmann::json;

bool is_frame_set_name(const std::string& name) {
  if (name == "frames.json") return true;
  constexpr std::size_t kDigits = 4;  // step_%04d.png: four digits or more
  const std::string head = "step_", tail = ".png";
  if (name.size() < head.size() + kDigits + tail.size() || name.rfind(head, 0) != 0 ||
      name.compare(name.size() - tail.size(), tail.size(), tail) != 0)
    return false;
  for (std::size_t i = head.size(); i < name.size() - tail.size(); ++i)
    if (name[i] < '0' || name[i] > '9') return false;
  return true;
}

std::string step_png(const fs::path& dir, int step) {
  char name[32];
  std::snprintf(name, sizeof name, "step_%04d.png", step);
  return (dir / name).string();
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

std::pair<int, int> part_frames(int frames, int part, int parts) {
  assert(parts >= 1 && part >= 0 && part < parts);
  const auto at = [&](int p) { return int(std::int64_t(frames) * p / parts); };
  return {at(part), at(part + 1)};
}

json merge_part_frames(const std::vector<json>& parts) {
  if (parts.empty()) throw tsp::FormatError("frames.json: no parts to join");
  int passes = 0;
  for (std::size_t r = 0; r < parts.size(); ++r) {
    const json& p = parts[r];
    const std::string name = "frames.json of rank " + std::to_string(r);
    if (!p.is_object() || !p.contains("frames") || !p["frames"].is_array())
      throw tsp::FormatError(name + ": expected an object with a frames array");
    for (const json& f : p["frames"]) {
      if (!f.is_object() || !f.contains("pass") || !f["pass"].is_number_integer() ||
          !f.contains("ms") || !f["ms"].is_number())
        throw tsp::FormatError(name + ": expected frames with an integer pass and a number ms");
      passes = std::max(passes, f["pass"].get<int>());
    }
  }
  json merged = parts[0];
  merged["frames"] = json::array();
  json contexts = json::array();
  double metric_ms = 0;
  for (int pass = 1; pass <= passes; ++pass)
    for (const json& p : parts)
      for (const json& f : p["frames"])
        if (f["pass"].get<int>() == pass) merged["frames"].push_back(f);
  for (std::size_t r = 0; r < parts.size(); ++r) {
    const json& p = parts[r];
    const double ms = p.value("metric_ms", 0.0);
    metric_ms = std::max(metric_ms, ms);
    contexts.push_back({{"rank", r},
                        {"context", p.value("context", "")},
                        {"renderer", p.value("renderer", "")},
                        {"gl_vendor", p.value("gl_vendor", "")},
                        {"metric_ms", ms},
                        {"frames", p["frames"].size()}});
  }
  std::vector<double> last;
  for (const json& f : merged["frames"])
    if (f["pass"].get<int>() == passes) last.push_back(f["ms"].get<double>());
  merged["metric_ms"] = metric_ms;
  merged["median_ms"] = median(std::move(last));
  merged["ranks"] = parts.size();
  merged["rank_contexts"] = std::move(contexts);
  return merged;
}

}  // namespace tspgl
