// Follows the VTKHDF file format specification 2.x (VTK documentation "VTKHDF File Format",
// "Unstructured grid" and "Temporal/Transient Data"):
//  - /VTKHDF: NumberOfPoints, NumberOfCells, NumberOfConnectivityIds (one entry per partition),
//    Points [Σ points, 3], Types [Σ cells] (uint8), Offsets [Σ (cells + 1)] (per partition, from
//    0), Connectivity [Σ ids] (per partition, point indices local to it), PointData/<name>,
//    CellData/<name> ([n] or [n, components]).
//  - Transient files add /VTKHDF/Steps (attribute NSteps) with, per step, PartOffsets and
//    NumberOfParts (which partitions), PointOffsets, CellOffsets, ConnectivityIdOffsets (where
//    the step's rows start) and PointDataOffsets/<name>, CellDataOffsets/<name>; a step's
//    Offsets rows start at CellOffsets + PartOffsets (each partition stores cells + 1 offsets).
#include "tsp/source/vtkhdf_mesh_source.h"

#include <hdf5.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <mutex>
#include <optional>

#include "tsp/core/error.h"
#include "tsp/core/file_check.h"
#include "tsp/hdf5/hdf5_handle.h"
#include "tsp/hdf5/hdf5_lock.h"
#include "tsp/hdf5/hdf5_values.h"
#include "tsp/source/vtk/vtk_document.h"

namespace tsp::io {
namespace {

using h5::Handle;

constexpr const char* kRoot = "/VTKHDF";
// VTKHDF major versions read (as for image data).
constexpr int kMaxMajorVersion = 2;

// A dataset's shape; throws FormatError when it cannot be opened.
std::vector<hsize_t> shape_of(hid_t file, const std::string& name, const std::string& where) {
  Handle ds(H5Dopen2(file, name.c_str(), H5P_DEFAULT));
  if (!ds) throw FormatError(where + ": dataset " + name + " is missing");
  return h5::dataset_shape(ds.get());
}

// Rows [start, start + count) of a 1-D or 2-D dataset as T (H5T_NATIVE_DOUBLE or
// H5T_NATIVE_LLONG), `cols` values per row (0: whatever the dataset has; returned in cols).
template <typename T>
std::vector<T> read_rows(hid_t file, const std::string& name, std::int64_t start,
                         std::int64_t count, int& cols, hid_t mem_type, bool integers,
                         const std::string& where) {
  const std::string dw = where + ", dataset " + name;
  Handle ds(H5Dopen2(file, name.c_str(), H5P_DEFAULT));
  if (!ds) throw FormatError(dw + ": missing");
  Handle type(H5Dget_type(ds.get()));
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_INTEGER && (integers || cls != H5T_FLOAT))
    throw FormatError(dw + ": is " + describe_h5_type(type.get()) + ", expected " +
                      (integers ? "integers" : "numbers"));
  std::vector<hsize_t> shape = h5::dataset_shape(ds.get());
  if (shape.empty() || shape.size() > 2)
    throw FormatError(dw + ": has " + std::to_string(shape.size()) +
                      " dimensions, expected 1 (or 2 with components)");
  const int have = shape.size() == 2 ? int(shape[1]) : 1;
  if (cols == 0) cols = have;
  if (have != cols || have < 1 || have > 64)
    throw FormatError(dw + ": has " + std::to_string(have) + " components, expected " +
                      std::to_string(cols));
  if (start < 0 || count < 0 || std::uint64_t(start) > shape[0] ||
      std::uint64_t(count) > shape[0] - std::uint64_t(start))
    throw FormatError(dw + ": rows " + std::to_string(start) + ".." +
                      std::to_string(start + count) + " requested, the dataset has " +
                      std::to_string(shape[0]));
  std::vector<T> out(std::size_t(count) * std::size_t(cols));
  if (count == 0) return out;
  Handle space(H5Dget_space(ds.get()));
  hsize_t off[2] = {hsize_t(start), 0}, cnt[2] = {hsize_t(count), hsize_t(cols)};
  H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, off, nullptr, cnt, nullptr);
  Handle mem(H5Screate_simple(int(shape.size()), cnt, nullptr));
  if (H5Dread(ds.get(), mem_type, mem.get(), space.get(), H5P_DEFAULT, out.data()) < 0)
    throw FormatError(dw + ": cannot be read");
  return out;
}

std::vector<std::int64_t> ints(hid_t file, const std::string& name, std::int64_t start,
                               std::int64_t count, const std::string& where) {
  int cols = 1;
  std::vector<long long> v =
      read_rows<long long>(file, name, start, count, cols, H5T_NATIVE_LLONG, true, where);
  return std::vector<std::int64_t>(v.begin(), v.end());
}

// One value of a per-step (or per-partition) table.
std::int64_t entry(hid_t file, const std::string& name, std::int64_t index,
                   const std::string& where) {
  return ints(file, name, index, 1, where)[0];
}


// Where step t's rows start in each table (all 0 and one partition for a static file).
// /VTKHDF's Version, when the file has one: major 1 or 2, as for image data. Throws FormatError.
void check_version(hid_t file, const std::string& path) {
  Handle root(H5Gopen2(file, kRoot, H5P_DEFAULT));
  if (!root) return;  // (resolve says what is missing)
  auto version = numeric_attribute(root.get(), "Version", path + ", /VTKHDF");
  if (!version) return;  // version 1 files may have none
  if (version->size() != 2)
    throw FormatError(path + ", /VTKHDF: attribute Version is not [major, minor]");
  const double major = (*version)[0];
  if (!(major >= 1 && major <= kMaxMajorVersion))
    throw FormatError(path + ", /VTKHDF: VTKHDF major version " +
                      (std::fabs(major) < 1e9 ? std::to_string(std::llround(major)) : "out of range") +
                      ", expected 1 or 2");
}

// Step times: finite and strictly increasing, as .pvd and .series lists must be. Throws
// FormatError naming where and the first bad entry.
void check_times(const std::vector<double>& times, const std::string& where) {
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (!std::isfinite(times[i]))
      throw FormatError(where + ": time of step " + std::to_string(i) + " is not a finite number");
    if (i > 0 && !(times[i] > times[i - 1]))
      throw FormatError(where + ": time of step " + std::to_string(i) + " (" +
                        std::to_string(times[i]) + ") is not after step " + std::to_string(i - 1) +
                        "'s (" + std::to_string(times[i - 1]) +
                        "); times must increase from step to step");
  }
}

struct StepRows {
  std::int64_t part = 0, parts = 1, points = 0, cells = 0, conn = 0, data = 0;
};

class VtkhdfMeshSource final : public MeshSource {
 public:
  VtkhdfMeshSource(std::string input, std::vector<std::string> files, FieldSpec field,
                   h5::External external)
      : input_(std::move(input)),
        files_(std::move(files)),
        field_(std::move(field)),
        external_(external) {
    std::lock_guard lock(hdf5_mutex());
    h5::silence_errors();
    Handle f = h5::open_file_readonly(files_[0], external_);
    check_version(f.get(), files_[0]);
    resolve(f.get(), files_[0]);
    transient_ = files_.size() == 1 && h5::exists(f.get(), "/VTKHDF/Steps");
    steps_ = int(files_.size());
    if (transient_) {
      Handle g(H5Gopen2(f.get(), "/VTKHDF/Steps", H5P_DEFAULT));
      auto n = numeric_attribute(g.get(), "NSteps", files_[0] + ", /VTKHDF/Steps");
      if (!n || n->size() != 1 || (*n)[0] < 1 || (*n)[0] > 1e7)
        throw FormatError(files_[0] + ": /VTKHDF/Steps attribute NSteps missing or not in 1..1e7");
      steps_ = int((*n)[0]);
      if (h5::exists(f.get(), "/VTKHDF/Steps/Values")) {
        int cols = 1;
        times_ = read_rows<double>(f.get(), "/VTKHDF/Steps/Values", 0, steps_, cols,
                                   H5T_NATIVE_DOUBLE, false, files_[0]);
        check_times(times_, files_[0] + ", /VTKHDF/Steps/Values");
      }
    }
  }

  int steps() const override { return steps_; }
  std::vector<std::string> files() const override { return files_; }
  std::vector<double> times() const override { return times_; }
  std::string field() const override { return field_.text(); }
  std::string describe() const override {
    return input_ + ", " + (cells_ ? "CellData " : "PointData ") + field_.name +
           (steps_ > 1 ? " (" + std::to_string(steps_) + " VTKHDF steps)" : "");
  }

  Mesh read_step(int t) override {
    assert(t >= 0 && t < steps_);
    std::lock_guard lock(hdf5_mutex());
    const std::string& path = transient_ ? files_[0] : files_[std::size_t(t)];
    Handle f = h5::open_file_readonly(path, external_);
    const std::string where = path + (transient_ ? ", step " + std::to_string(t) : "");
    StepRows rows = step_rows(f.get(), t, where);
    Mesh m;
    m.cell_values = cells_;
    m.offsets.push_back(0);
    if (h5::exists(f.get(), "/VTKHDF/FaceConnectivity") ||
        h5::exists(f.get(), "/VTKHDF/PolyhedronToFaces"))
      throw FormatError(where + ": holds polyhedra (FaceConnectivity); VTKHDF polyhedra are not "
                        "read yet, write the mesh as .vtu instead");
    std::int64_t offset_row = rows.cells + rows.part, data_row = rows.data;
    const std::string data_name =
        std::string(cells_ ? "/VTKHDF/CellData/" : "/VTKHDF/PointData/") + field_.name;
    for (std::int64_t p = rows.part; p < rows.part + rows.parts; ++p) {
      const std::string pw = where + ", partition " + std::to_string(p);
      const std::int64_t np = entry(f.get(), "/VTKHDF/NumberOfPoints", p, pw);
      const std::int64_t nc = entry(f.get(), "/VTKHDF/NumberOfCells", p, pw);
      const std::int64_t nconn = entry(f.get(), "/VTKHDF/NumberOfConnectivityIds", p, pw);
      if (np < 0 || nc < 0 || nconn < 0)
        throw FormatError(pw + ": negative NumberOfPoints, NumberOfCells or "
                          "NumberOfConnectivityIds");
      const std::int64_t base = m.point_count(), conn_base = std::int64_t(m.connectivity.size());
      int three = 3;
      std::vector<double> xyz = read_rows<double>(f.get(), "/VTKHDF/Points", rows.points, np,
                                                  three, H5T_NATIVE_DOUBLE, false, pw);
      m.points.insert(m.points.end(), xyz.begin(), xyz.end());
      const std::vector<std::int64_t> offs = ints(f.get(), "/VTKHDF/Offsets", offset_row, nc + 1, pw);
      if (offs[0] != 0 || offs[std::size_t(nc)] != nconn)
        throw FormatError(pw + ", dataset /VTKHDF/Offsets: runs from " + std::to_string(offs[0]) +
                          " to " + std::to_string(offs[std::size_t(nc)]) + ", expected 0 to " +
                          "NumberOfConnectivityIds " + std::to_string(nconn));
      const std::vector<std::int64_t> conn =
          ints(f.get(), "/VTKHDF/Connectivity", rows.conn, nconn, pw);
      for (std::size_t k = 0; k < conn.size(); ++k) {
        if (conn[k] < 0 || conn[k] >= np)
          throw FormatError(pw + ", dataset /VTKHDF/Connectivity: entry " + std::to_string(k) +
                            " is point " + std::to_string(conn[k]) + ", expected 0.." +
                            std::to_string(np - 1));
        m.connectivity.push_back(conn[k] + base);
      }
      const std::vector<std::int64_t> types = ints(f.get(), "/VTKHDF/Types", rows.cells, nc, pw);
      for (std::int64_t c = 0; c < nc; ++c) {
        const std::int64_t a = offs[std::size_t(c)], b = offs[std::size_t(c) + 1];
        if (b < a)
          throw FormatError(pw + ", dataset /VTKHDF/Offsets: entry " + std::to_string(c + 1) +
                            " is below the previous one");
        m.offsets.push_back(conn_base + b);
        if (!is_supported_cell_type(types[std::size_t(c)]))
          throw FormatError(pw + ", dataset /VTKHDF/Types: cell " + std::to_string(c) +
                            " has type " + std::to_string(types[std::size_t(c)]) +
                            ", expected tetra (10), voxel (11), hexahedron (12), wedge (13) or "
                            "pyramid (14)");
        m.types.push_back(CellType(types[std::size_t(c)]));
      }
      const std::int64_t tuples = cells_ ? nc : np;
      int comps = components_;
      std::vector<double> v = read_rows<double>(f.get(), data_name, data_row, tuples, comps,
                                                H5T_NATIVE_DOUBLE, false, pw);
      std::vector<float> vf(v.size());
      for (std::size_t i = 0; i < v.size(); ++i) vf[i] = float(v[i]);
      vf = FieldSpec::reduce(vf, comps, field_, pw + ", dataset " + data_name);
      m.values.insert(m.values.end(), vf.begin(), vf.end());
      rows.points += np;
      rows.cells += nc;
      rows.conn += nconn;
      offset_row += nc + 1;
      data_row += tuples;
    }
    check_mesh(m, where);
    return m;
  }

 private:
  void resolve(hid_t file, const std::string& path);
  StepRows step_rows(hid_t file, int t, const std::string& where) const;

  std::string input_;
  std::vector<std::string> files_;
  FieldSpec field_;
  bool cells_ = false;
  int components_ = 1;
  bool transient_ = false;
  int steps_ = 1;
  std::vector<double> times_;
  h5::External external_;
};

void VtkhdfMeshSource::resolve(hid_t file, const std::string& path) {
  const std::vector<std::string> points = h5::datasets_in(file, "/VTKHDF/PointData");
  const std::vector<std::string> cells = h5::datasets_in(file, "/VTKHDF/CellData");
  const std::string listing =
      "PointData: " + join_names(points) + "; CellData: " + join_names(cells);
  auto has = [](const std::vector<std::string>& v, const std::string& n) {
    return std::find(v.begin(), v.end(), n) != v.end();
  };
  if (field_.name.empty()) {
    if (points.size() == 1 && cells.empty()) {
      field_.name = points[0];
    } else if (points.empty() && cells.size() == 1) {
      field_.name = cells[0];
      cells_ = true;
    } else {
      throw FormatError(path + ": no field given and no single array to default to (" + listing +
                        "); name one with --field");
    }
  } else if (has(points, field_.name)) {
  } else if (has(cells, field_.name)) {
    cells_ = true;
  } else {
    throw FormatError(path + ": field '" + field_.name + "' not found; available arrays: " +
                      listing);
  }
  const std::string name =
      std::string(cells_ ? "/VTKHDF/CellData/" : "/VTKHDF/PointData/") + field_.name;
  std::vector<hsize_t> shape = shape_of(file, name, path);
  components_ = shape.size() == 2 ? int(shape[1]) : 1;
  FieldSpec::reduce(std::vector<float>(std::size_t(std::max(components_, 1))), components_,
                    field_, path + ", dataset " + name);
}

StepRows VtkhdfMeshSource::step_rows(hid_t file, int t, const std::string& where) const {
  StepRows r;
  if (!transient_) return r;
  const std::string s = "/VTKHDF/Steps/";
  r.part = entry(file, s + "PartOffsets", t, where);
  r.parts = h5::exists(file, s + "NumberOfParts") ? entry(file, s + "NumberOfParts", t, where) : 1;
  r.points = entry(file, s + "PointOffsets", t, where);
  r.cells = entry(file, s + "CellOffsets", t, where);
  r.conn = entry(file, s + "ConnectivityIdOffsets", t, where);
  const std::string data = s + (cells_ ? "CellDataOffsets/" : "PointDataOffsets/") + field_.name;
  r.data = h5::exists(file, data) ? entry(file, data, t, where) : (cells_ ? r.cells : r.points);
  if (r.part < 0 || r.parts < 1 || r.parts > 1 << 20)
    throw FormatError(where + ": Steps/PartOffsets or NumberOfParts out of range");
  return r;
}

}  // namespace

bool is_vtkhdf_unstructured(const std::string& path, h5::External external) {
  try {
    std::lock_guard lock(hdf5_mutex());
    h5::silence_errors();
    require_regular_file(path, "input");  // before H5Fis_hdf5 opens it: a FIFO would block
    if (H5Fis_hdf5(path.c_str()) <= 0) return false;
    Handle f = h5::open_file_readonly(path, external);
    return is_vtkhdf_unstructured(f.get());
  } catch (const std::exception&) {
    return false;
  }
}

bool is_vtkhdf_unstructured(hid_t file) {
  try {
    if (!h5::exists(file, kRoot)) return false;
    Handle root(H5Gopen2(file, kRoot, H5P_DEFAULT));
    auto type = string_attribute(root.get(), "Type", "VTKHDF");
    if (type) return *type == "UnstructuredGrid";
    return h5::exists(file, "/VTKHDF/Connectivity");
  } catch (const std::exception&) {
    return false;
  }
}

std::unique_ptr<MeshSource> open_vtkhdf_mesh_source(const std::string& input,
                                                    const std::vector<std::string>& files,
                                                    const FieldSpec& field,
                                                    h5::External external) {
  if (files.empty()) throw IoError(input + ": no files match");
  for (const std::string& f : files) {
    {  // a refused external link or storage says so (the probe below only says "not VTKHDF")
      std::lock_guard lock(hdf5_mutex());
      h5::open_file_readonly(f, external);
    }
    if (!is_vtkhdf_unstructured(f, external))
      throw FormatError(f + ": not a VTKHDF UnstructuredGrid file (no /VTKHDF group of Type "
                        "UnstructuredGrid)");
  }
  return std::make_unique<VtkhdfMeshSource>(input, files, field, external);
}

}  // namespace tsp::io
