#include "tsp/source/open_mesh_source.h"

#include <algorithm>
#include <cassert>
#include <cctype>
#include <filesystem>
#include <pugixml.hpp>

#include "tsp/core/error.h"
#include "tsp/core/file_check.h"
#include "tsp/source/raw_source.h"
#include "tsp/source/series_list.h"
#include "tsp/source/mesh_file.h"
#include "tsp/source/plot3d_source.h"
#include "tsp/source/vtkhdf_mesh_source.h"

namespace tsp {
namespace {


bool is_hdf5_name(const std::string& s) {
  for (const char* ext : {".hdf", ".vtkhdf", ".h5", ".hdf5"})
    if (io::has_suffix(s, ext)) return true;
  return false;
}

bool names_unstructured(const std::string& file) {
  return io::is_mesh_file_name(file) || io::has_suffix(file, ".vtm");
}

// A series of .vtu or .vts files (a .vtm step reads its volume block).
class MeshFileSeriesSource final : public MeshSource {
 public:
  MeshFileSeriesSource(std::string input, std::vector<io::StepFile> steps, io::MeshField field,
                  bool named_times)
      : input_(std::move(input)),
        steps_(std::move(steps)),
        field_(std::move(field)),
        named_times_(named_times) {}

  int steps() const override { return int(steps_.size()); }
  std::vector<std::string> files() const override {
    std::vector<std::string> all{input_};
    for (const io::StepFile& s : steps_) {
      all.push_back(s.file);
      if (io::has_suffix(s.file, ".vtm")) {  // and the .vtu it names: never written over either
        try {
          all.push_back(io::vtm_volume_block(s.file));
        } catch (const Error&) {
        }
      }
    }
    return all;
  }
  std::vector<double> times() const override {
    std::vector<double> t;
    if (named_times_)
      for (const io::StepFile& s : steps_) t.push_back(s.time);
    return t;
  }
  std::string field() const override { return field_.spec.text(); }
  std::string describe() const override {
    return input_ + ", " + (field_.cells ? "CellData " : "PointData ") + field_.spec.name +
           (steps_.size() > 1 ? " (" + std::to_string(steps_.size()) + " steps)" : "");
  }
  Mesh read_step(int t) override {
    assert(t >= 0 && t < steps());
    std::unique_ptr<io::MeshFile> file = io::open_mesh_file(volume_file(steps_[std::size_t(t)].file));
    io::MeshField f = file->resolve(field_.spec);
    if (f.cells != field_.cells)
      throw FormatError(file->path() + ": field " + f.spec.name + " is " +
                        (f.cells ? "CellData" : "PointData") + " here but " +
                        (field_.cells ? "CellData" : "PointData") + " in the first step");
    return file->read(f);
  }

  Aabb bounds(int t) override {
    assert(t >= 0 && t < steps());
    return io::open_mesh_file(volume_file(steps_[std::size_t(t)].file))->bounds();
  }

  // A step's .vtu or .vts: itself, or a .vtm's volume block.
  static std::string volume_file(const std::string& file) {
    return io::has_suffix(file, ".vtm") ? io::vtm_volume_block(file) : file;
  }

 private:
  std::string input_;
  std::vector<io::StepFile> steps_;
  io::MeshField field_;
  bool named_times_;  // the steps came from a .pvd or .series list
};

std::unique_ptr<MeshSource> open_vtu_steps(const std::string& input,
                                           std::vector<io::StepFile> steps,
                                           const FieldSpec& spec, bool named_times) {
  io::order_steps(input, steps);
  for (const io::StepFile& s : steps) {
    try {
      require_regular_file(s.file, "step file");
      if (io::has_suffix(s.file, ".vtm")) io::vtm_volume_block(s.file);  // its block, too
    } catch (const IoError& e) {
      throw IoError(s.file == input ? std::string(e.what()) : input + ": " + e.what());
    }
  }
  const std::string first_file = MeshFileSeriesSource::volume_file(steps[0].file);
  for (const io::StepFile& s : steps)
    if (io::has_suffix(MeshFileSeriesSource::volume_file(s.file), ".vts") !=
        io::has_suffix(first_file, ".vts"))
      throw FormatError(input + ": step " + s.file + " and step " + steps[0].file +
                        " are of different kinds (.vts and .vtu); expected one kind of grid");
  io::MeshField field = io::open_mesh_file(first_file)->resolve(spec);
  return std::make_unique<MeshFileSeriesSource>(input, std::move(steps), field, named_times);
}

// The steps a list or pattern names.
std::vector<io::StepFile> listed_steps(const std::string& input) {
  std::error_code ec;
  if (!std::filesystem::exists(input, ec) && io::is_file_pattern(input)) {
    std::vector<io::StepFile> steps;
    for (const std::string& f : io::expand_file_pattern(input))
      steps.push_back({f, double(steps.size())});
    return steps;
  }
  if (io::has_suffix(input, ".pvd")) return io::read_pvd(input);
  if (io::has_suffix(input, ".series")) return io::read_file_series(input);
  return {{input, 0}};
}

h5::External external_policy(bool allow) {
  return allow ? h5::External::allow : h5::External::refuse;
}

}  // namespace

bool is_mesh_input(const std::string& input, bool allow_external) {
  try {
    if (io::is_mesh_file_name(input) || io::has_suffix(input, ".vtm") ||
        io::has_suffix(input, ".vtu.series") || io::has_suffix(input, ".vts.series") ||
        io::has_suffix(input, ".vtm.series") || is_plot3d_input(input))
      return true;
    if (io::has_suffix(input, ".pvd")) {
      std::vector<io::StepFile> steps = io::read_pvd(input);
      return !steps.empty() && names_unstructured(steps[0].file);
    }
    if (!is_hdf5_name(input)) return false;
    std::error_code ec;
    if (std::filesystem::exists(input, ec))
      return io::is_vtkhdf_unstructured(input, external_policy(allow_external));
    if (!io::is_file_pattern(input)) return false;
    std::vector<std::string> files = io::expand_file_pattern(input);
    return !files.empty() &&
           io::is_vtkhdf_unstructured(files[0], external_policy(allow_external));
  } catch (const std::exception&) {
    return false;
  }
}

std::unique_ptr<MeshSource> open_mesh_source(const std::string& input, const std::string& field,
                                             bool allow_external, const std::string& plot3d_grid) {
  const FieldSpec spec = FieldSpec::parse(field);
  if (is_plot3d_input(input)) return open_plot3d_source(input, plot3d_grid, spec);
  std::vector<io::StepFile> steps = listed_steps(input);
  if (steps.size() == 1 && steps[0].file == input) require_regular_file(input, "input");
  if (!steps.empty() && is_hdf5_name(steps[0].file)) {
    std::vector<std::string> files;
    for (const io::StepFile& s : steps) files.push_back(s.file);
    return io::open_vtkhdf_mesh_source(input, files, spec, external_policy(allow_external));
  }
  const bool named = io::has_suffix(input, ".pvd") || io::has_suffix(input, ".series");
  return open_vtu_steps(input, std::move(steps), spec, named);
}

}  // namespace tsp
