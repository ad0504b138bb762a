#include "tsp/source/vti_source.h"

#include <algorithm>
#include <cmath>
#include <cassert>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include "tsp/core/error.h"
#include "tsp/core/file_check.h"
#include "tsp/source/raw_source.h"
#include "tsp/source/vtk/vti_file.h"

namespace tsp::io {
namespace {

namespace fs = std::filesystem;

// One step of a series: its file and time value (for ordering and messages).
struct StepFile {
  std::string file;
  double time = 0;
};

// A time series of .vti files (one file for a plain .vti); all steps share one grid.
class VtiSeriesSource final : public VolumeSource {
 public:
  VtiSeriesSource(std::string input, std::vector<std::string> files, VtiField field, Dims dims)
      : input_(std::move(input)), files_(std::move(files)), field_(std::move(field)), dims_(dims) {}

  Dims dims() const override { return dims_; }
  int steps() const override { return int(files_.size()); }
  std::vector<std::string> files() const override {
    std::vector<std::string> all = files_;
    if (std::find(all.begin(), all.end(), input_) == all.end()) all.push_back(input_);
    return all;
  }
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
                                          const SourceOptions& options) {
  if (steps.empty()) throw FormatError(input + ": lists no data files, expected at least one");
  std::stable_sort(steps.begin(), steps.end(),
                   [](const StepFile& a, const StepFile& b) { return a.time < b.time; });
  for (std::size_t i = 1; i < steps.size(); ++i)
    if (steps[i].time == steps[i - 1].time)
      throw FormatError(input + ": " + steps[i - 1].file + " and " + steps[i].file +
                        " share time " + std::to_string(steps[i].time) +
                        "; several parts per time step are not supported");
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
  return std::make_unique<VtiSeriesSource>(input, std::move(files), field, dims);
}

std::string resolve_relative(const std::string& list_file, const std::string& name) {
  fs::path p(name);
  if (p.is_absolute()) return p.string();
  return (fs::path(list_file).parent_path() / p).string();
}

void require_file(const std::string& path) { require_regular_file(path, "input"); }

}  // namespace

std::unique_ptr<VolumeSource> open_vti_source(const std::string& path,
                                              const SourceOptions& options) {
  require_file(path);
  return open_series(path, {StepFile{path, 0}}, options);
}

std::unique_ptr<VolumeSource> open_pvd_source(const std::string& path,
                                              const SourceOptions& options) {
  require_file(path);
  pugi::xml_document doc;
  pugi::xml_parse_result res = doc.load_file(path.c_str());
  if (!res)
    throw FormatError(path + ": not well-formed XML (" + res.description() + " at byte " +
                      std::to_string(res.offset) + ")");
  pugi::xml_node root = doc.child("VTKFile");
  if (!root || std::string(root.attribute("type").value()) != "Collection")
    throw FormatError(path + ": expected <VTKFile type=\"Collection\">");
  pugi::xml_node collection = root.child("Collection");
  if (!collection) throw FormatError(path + ": no <Collection> element");
  std::vector<StepFile> steps;
  int index = 0;
  for (pugi::xml_node ds : collection.children("DataSet")) {
    const std::string dwhere = path + ", DataSet " + std::to_string(index++);
    if (!ds.attribute("file")) throw FormatError(dwhere + ": has no file attribute");
    if (!ds.attribute("timestep"))
      throw FormatError(dwhere + ": has no timestep attribute, expected one per step");
    std::string text = ds.attribute("timestep").value();
    std::size_t used = 0;
    double time = 0;
    try {
      time = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != text.size())
      throw FormatError(dwhere + ": timestep \"" + text + "\" is not a number");
    if (!std::isfinite(time))
      throw FormatError(dwhere + ": timestep \"" + text + "\" is not a finite number");
    steps.push_back({resolve_relative(path, ds.attribute("file").value()), time});
  }
  return open_series(path, std::move(steps), options);
}

std::unique_ptr<VolumeSource> open_vti_series_source(const std::string& path,
                                                     const SourceOptions& options) {
  require_file(path);
  std::ifstream in(path);
  if (!in) throw IoError(path + ": cannot be opened for reading");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw FormatError(path + ": not valid JSON (" + e.what() + ")");
  }
  if (!j.is_object() || !j.contains("file-series-version") || !j["file-series-version"].is_string())
    throw FormatError(path + ": no \"file-series-version\" string, expected \"1.0\"");
  std::string version = j["file-series-version"];
  if (version.rfind("1.", 0) != 0)
    throw FormatError(path + ": file-series-version \"" + version + "\", expected 1.x");
  if (!j.contains("files") || !j["files"].is_array())
    throw FormatError(path + ": no \"files\" array");
  std::vector<StepFile> steps;
  int index = 0;
  for (const auto& f : j["files"]) {
    const std::string fwhere = path + ", files[" + std::to_string(index++) + "]";
    if (!f.is_object() || !f.contains("name") || !f["name"].is_string())
      throw FormatError(fwhere + ": expected an object with a \"name\" string");
    if (!f.contains("time") || !f["time"].is_number())
      throw FormatError(fwhere + ": expected a numeric \"time\"");
    steps.push_back(
        {resolve_relative(path, f["name"].get<std::string>()), f["time"].get<double>()});
  }
  return open_series(path, std::move(steps), options);
}

std::unique_ptr<VolumeSource> open_vti_pattern_source(const std::string& pattern,
                                                      const SourceOptions& options) {
  std::vector<StepFile> steps;
  for (const std::string& f : expand_file_pattern(pattern))
    steps.push_back({f, double(steps.size())});
  return open_series(pattern, std::move(steps), options);
}

}  // namespace tsp::io
