#include "jobs/play_input.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>

#include "jobs/calibration.h"
#include "tsp/core/error.h"
#include "tsp/hdf5/hdf5_handle.h"
#include "tsp/hdf5/hdf5_lock.h"
#include "tsp/source/open_mesh_source.h"
#include "tsp/voxelize/open_input.h"

namespace tspgl {

namespace fs = std::filesystem;

namespace {

// FNV-1a of text, for cache names.
std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  return h;
}

}  // namespace

bool is_tsp_file(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return false;
  std::lock_guard lock(tsp::hdf5_mutex());
  tsp::h5::silence_errors();
  if (H5Fis_hdf5(path.c_str()) <= 0) return false;
  tsp::h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  return f && H5Aexists(f.get(), "format") > 0;
}

bool has_input_extension(const std::string& name) {
  std::string lower = name;
  for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
  static constexpr const char* kSuffixes[] = {
      ".tsp", ".h5",  ".hdf5", ".hdf", ".he5",        ".nc",         ".nc4",        ".vtkhdf",
      ".vti", ".vtu", ".vts",  ".vtm", ".pvd", ".vti.series", ".vtu.series", ".vts.series",
      ".vtm.series", ".q", ".raw"};
  for (const char* s : kSuffixes) {
    const std::size_t n = std::char_traits<char>::length(s);
    if (lower.size() > n && lower.compare(lower.size() - n, n, s) == 0) return true;
  }
  return false;
}

std::string play_cache_path(const std::string& input, const PlayInputOptions& o,
                            const std::string& cache_dir) {
  std::error_code ec;
  const fs::path abs = fs::absolute(input, ec);
  std::string key = abs.string() + "|" + o.field + o.key;
  if (fs::is_regular_file(input, ec))  // (a pattern names no one file: its path alone)
    key += "|" + std::to_string(fs::file_size(input, ec)) + "|" +
           std::to_string(fs::last_write_time(input, ec).time_since_epoch().count());
  const std::string dir = cache_dir.empty() ? default_calibration_dir() : cache_dir;
  if (dir.empty())
    throw tsp::UsageError(input + " is not a .tsp file and there is no cache folder to build it "
                          "into (set HOME, XDG_CACHE_HOME or --cache-dir)");
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fnv1a(key)));
  return (fs::path(dir) / "builds" / (abs.filename().string() + "-" + hash + ".tsp")).string();
}

std::string prepare_play_input(const std::string& input, const PlayInputOptions& o,
                               const std::string& cache_dir, const PlayBuildHooks& hooks) {
  if (is_tsp_file(input)) return input;  // (a field then picks one of its fields)
  const std::string out = play_cache_path(input, o, cache_dir);
  if (is_tsp_file(out)) {
    hooks.say("play: " + input + " is not a .tsp file; playing " + out + ", built from it earlier");
    return out;
  }
  std::error_code ec;
  const fs::path builds = fs::path(out).parent_path();
  fs::create_directories(builds, ec);
  if (ec) throw tsp::IoError(builds.string() + ": cannot create the build cache: " + ec.message());
  if (o.adaptive) {
    if (o.field.find(',') != std::string::npos)
      throw tsp::UsageError("--octree-error builds one field; --field " + o.field +
                            " names several");
    if (!tsp::is_mesh_input(input, o.source.allow_external))
      throw tsp::UsageError("--octree-error: " + input +
                            " is not an unstructured mesh; regular grids are built without it");
    auto mesh = tsp::open_mesh_source(input, o.field, o.source.allow_external, o.source.plot3d_grid);
    hooks.say("play: " + input + " is not a .tsp file; building its adaptive octree into " + out +
              " (reused next time)");
    tsp::AdaptiveOptions ao = o.octree;
    ao.voxelize = o.voxelize;
    ao.build.field_name = o.field;
    ao.build.brick_size = 0;  // the default for the finest grid, as build picks it
    ao.build.threads = o.voxelize.sample.threads;
    hooks.build_adaptive(*mesh, out, ao);
    return out;
  }
  const auto open_field = [&](const std::string& field) {
    tsp::SourceOptions so = o.source;
    so.field = field;
    return tsp::open_input(input, so, o.voxelize);
  };
  // --field A,B,C: several fields, one tree each (the first shown), as `build` does.
  std::vector<std::string> fields;
  for (std::size_t p = 0; o.field.find(',') != std::string::npos && p <= o.field.size();) {
    std::size_t c = o.field.find(',', p);
    if (c == std::string::npos) c = o.field.size();
    fields.push_back(o.field.substr(p, c - p));
    p = c + 1;
  }
  std::unique_ptr<tsp::VolumeSource> first = open_field(fields.empty() ? o.field : fields[0]);
  hooks.say("play: " + input + " is not a .tsp file; building it into " + out +
            " (reused next time)");
  tsp::BuildOptions bo;
  bo.field_name = o.field;
  bo.brick_size = tsp::default_brick_size(first->dims());
  bo.threads = o.voxelize.sample.threads;
  if (fields.empty()) {
    hooks.build(*first, out, bo);
    return out;
  }
  auto open_with_first = [&](const std::string& field) {
    return first ? std::move(first) : open_field(field);
  };
  hooks.build_fields(open_with_first, fields, out, bo);
  return out;
}

}  // namespace tspgl
