#include "tsp/source/vti_source.h"

#include <algorithm>
#include <cmath>
#include <cassert>
#include <filesystem>
#include <fstream>

#include "tsp/core/error.h"
#include "tsp/core/file_check.h"
#include "tsp/source/raw_source.h"
#include "tsp/source/series_list.h"
#include "tsp/source/vtk/vti_file.h"

namespace tsp::io {
namespace {

namespace fs = std::filesystem;

// A time series of .vti files (one file for a plain .vti); all steps share one grid.
class VtiSeriesSource final : public VolumeSource {
 public:
  VtiSeriesSource(std::string input, std::vector<std::string> files, VtiField field, Dims dims)
      : input_(std::move(input)), files_(std::move(files)), field_(std::move(field)), dims_(dims) {}

  Dims dims() const override { return dims_; }
  std::array<double, 3> origin() const override { return {geometry_[0], geometry_[1], geometry_[2]}; }
  std::array<double, 3> spacing() const override { return {geometry_[3], geometry_[4], geometry_[5]}; }
  std::array<double, 6> geometry_{0, 0, 0, 1, 1, 1};  // of the first step
  std::vector<double> times_;                          // from a .pvd or .series list
  std::vector<double> times() const override { return times_; }
  int steps() const override { return int(files_.size()); }
  std::vector<std::string> files() const override {
    std::vector<std::string> all = files_;
    if (std::find(all.begin(), all.end(), input_) == all.end()) all.push_back(input_);
    return all;
  }
  std::string field() const override { return field_.name; }
  std::string describe() const override {
    return input_ + ", " + (field_.cells ? "CellData " : "PointData ") + field_.name +
           (files_.size() > 1 ? " (" + std::to_string(files_.size()) + " .vti steps)" : "");
  }

  void read_step(int t, std::span<float> out) override {
    assert(t >= 0 && t < steps());
    assert(std::int64_t(out.size()) == dims_.count());
    VtiFile file(files_[std::size_t(t)], false);
    VtiField f = checked_field(file, field_, dims_, files_[0]);
    file.read(f, out);
  }

  // The step's view of the series' field, checked to exist with the series' grid size.
  static VtiField checked_field(const VtiFile& file, const VtiField& want, Dims dims,
                                const std::string& first) {
    VtiField f = file.resolve(want.name);
    if (f.cells != want.cells)
      throw FormatError(file.path() + ": field " + want.name + " is " +
                        (f.cells ? "CellData" : "PointData") + " here but " +
                        (want.cells ? "CellData" : "PointData") + " in " + first);
    if (file.dims(f) != dims)
      throw FormatError(file.path() + ": grid " + to_string(file.dims(f)) + " differs from " +
                        to_string(dims) + " in " + first + "; all steps must have the same grid");
    return f;
  }

 private:
  std::string input_;
  std::vector<std::string> files_;
  VtiField field_;
  Dims dims_;
};

// Orders steps by time and builds the source, checking every step's header up front so a
// bad step fails at open rather than halfway through a build.
std::unique_ptr<VolumeSource> open_series(const std::string& input, std::vector<StepFile> steps,
                                          const SourceOptions& options, bool named_times) {
  order_steps(input, steps);
  std::vector<std::string> files;
  for (const StepFile& s : steps) {
    try {
      require_regular_file(s.file, "step file");
    } catch (const IoError& e) {
      throw IoError(input + ": " + e.what());
    }
    files.push_back(s.file);
  }
  VtiFile first(files[0], true);
  VtiField field = first.resolve(options.field);
  Dims dims = first.dims(field);
  for (std::size_t i = 1; i < files.size(); ++i)
    VtiSeriesSource::checked_field(VtiFile(files[i], true), field, dims, files[0]);
  const std::array<double, 6> geometry = first.geometry(field);
  std::vector<double> times;
  if (named_times)
    for (const StepFile& st : steps) times.push_back(st.time);
  auto source = std::make_unique<VtiSeriesSource>(input, std::move(files), field, dims);
  source->geometry_ = geometry;
  source->times_ = std::move(times);
  return source;
}

void require_file(const std::string& path) { require_regular_file(path, "input"); }

}  // namespace

std::unique_ptr<VolumeSource> open_vti_source(const std::string& path,
                                              const SourceOptions& options) {
  require_file(path);
  return open_series(path, {StepFile{path, 0}}, options, false);
}

std::unique_ptr<VolumeSource> open_pvd_source(const std::string& path,
                                              const SourceOptions& options) {
  require_file(path);
  return open_series(path, read_pvd(path), options, true);
}

std::unique_ptr<VolumeSource> open_vti_series_source(const std::string& path,
                                                     const SourceOptions& options) {
  require_file(path);
  return open_series(path, read_file_series(path), options, true);
}

std::unique_ptr<VolumeSource> open_vti_pattern_source(const std::string& pattern,
                                                      const SourceOptions& options) {
  std::vector<StepFile> steps;
  for (const std::string& f : expand_file_pattern(pattern))
    steps.push_back({f, double(steps.size())});
  return open_series(pattern, std::move(steps), options, false);
}

}  // namespace tsp::io
