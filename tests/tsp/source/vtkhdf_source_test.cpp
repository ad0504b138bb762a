#include "tsp/source/vtkhdf_source.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <vector>

#include "support/paths.h"
#include "support/reader_formula.h"
#include "tsp/core/error.h"
#include "tsp/hdf5/hdf5_handle.h"

namespace tsp {
namespace {

namespace fs = std::filesystem;
using namespace tsptest;  // the reader fixtures' formula, grids and helpers

// The fixture's transient file replays stored volumes 0, 1, 1, 2 (Steps/*DataOffsets).
const std::vector<double> kStoredIndex = {0, 1, 1, 2};

TEST(VtkHdfSource, TransientPointDataFollowsTheOffsetsTable) {
  auto s = open_field(h5_fixture("vtkhdf_transient.hdf"), "f");
  expect_steps(*s, kFixtureDims, kStoredIndex);
  EXPECT_NE(s->describe().find("PointData/f"), std::string::npos) << s->describe();
}

TEST(VtkHdfSource, EmptyFieldUsesTheActiveScalars) {
  expect_steps(*open_field(h5_fixture("vtkhdf_transient.hdf"), ""), kFixtureDims, kStoredIndex);
}

TEST(VtkHdfSource, CellDataIsReadAsTheGridOfCells) {
  auto s = open_field(h5_fixture("vtkhdf_transient.hdf"), "c");
  expect_steps(*s, kFixtureCellDims, kStoredIndex);
}

TEST(VtkHdfSource, VectorFieldIsRejected) {
  std::string msg =
      error_of<FormatError>([] { open_field(h5_fixture("vtkhdf_transient.hdf"), "v"); });
  EXPECT_NE(msg.find("vtkhdf_transient.hdf"), std::string::npos) << msg;
  EXPECT_NE(msg.find("field v has 3 components; a scalar field is expected"), std::string::npos)
      << msg;
}

TEST(VtkHdfSource, MissingFieldListsArrays) {
  std::string msg =
      error_of<FormatError>([] { open_field(h5_fixture("vtkhdf_transient.hdf"), "zz"); });
  EXPECT_NE(msg.find("'zz'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("PointData: f, v"), std::string::npos) << msg;
  EXPECT_NE(msg.find("CellData: c"), std::string::npos) << msg;
}

TEST(VtkHdfSource, StaticImageDataIsOneStep) {
  // This file's Type attribute is a variable-length string (h5py's default).
  auto s = open_field(h5_fixture("vtkhdf_static.hdf"), "");
  expect_steps(*s, kFixtureDims, {0});
}

TEST(VtkHdfSource, UnstructuredGridIsRejectedByType) {
  fs::path can = tsptest::shared_data_dir() / "crushing-can" / "can_0.hdf";
  if (!fs::exists(can)) GTEST_SKIP() << "shared data absent: " << can;
  std::string msg = error_of<FormatError>([&] { open_field(can.string(), "EQPS"); });
  EXPECT_NE(msg.find("UnstructuredGrid"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected \"ImageData\""), std::string::npos) << msg;
}

// ---- malformed files written here with the HDF5 C API ---------------------------------------

// Builds a small VTKHDF ImageData file; each test breaks one thing.
struct Writer {
  h5::Handle file;
  h5::Handle root;
  explicit Writer(const fs::path& p) {
    h5::silence_errors();
    file = h5::Handle(H5Fcreate(p.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
    root = h5::Handle(H5Gcreate2(file.get(), "VTKHDF", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  }
  void ints(hid_t loc, const char* name, std::vector<long long> v) {
    hsize_t n = v.size();
    h5::Handle space(H5Screate_simple(1, &n, nullptr));
    h5::Handle a(H5Acreate2(loc, name, H5T_NATIVE_LLONG, space.get(), H5P_DEFAULT, H5P_DEFAULT));
    H5Awrite(a.get(), H5T_NATIVE_LLONG, v.data());
  }
  void text(hid_t loc, const char* name, const std::string& s) {
    h5::Handle type(H5Tcopy(H5T_C_S1));
    H5Tset_size(type.get(), s.size());
    h5::Handle space(H5Screate(H5S_SCALAR));
    h5::Handle a(H5Acreate2(loc, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT));
    H5Awrite(a.get(), type.get(), s.data());
  }
  hid_t group(const char* path) {
    groups.emplace_back(H5Gcreate2(file.get(), path, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    return groups.back().get();
  }
  void floats(const char* path, std::vector<hsize_t> shape) {
    hsize_t n = 1;
    for (hsize_t d : shape) n *= d;
    std::vector<float> v(n, 1.0f);
    h5::Handle space(H5Screate_simple(int(shape.size()), shape.data(), nullptr));
    h5::Handle d(H5Dcreate2(file.get(), path, H5T_NATIVE_FLOAT, space.get(), H5P_DEFAULT,
                            H5P_DEFAULT, H5P_DEFAULT));
    H5Dwrite(d.get(), H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  }
  void longs(const char* path, std::vector<long long> v) {
    hsize_t n = v.size();
    h5::Handle space(H5Screate_simple(1, &n, nullptr));
    h5::Handle d(H5Dcreate2(file.get(), path, H5T_NATIVE_LLONG, space.get(), H5P_DEFAULT,
                            H5P_DEFAULT, H5P_DEFAULT));
    H5Dwrite(d.get(), H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  }
  // A valid header for a 5 × 4 × 3 image.
  void header(std::vector<long long> version = {2, 1}, const std::string& type = "ImageData") {
    ints(root.get(), "Version", version);
    text(root.get(), "Type", type);
    ints(root.get(), "WholeExtent", {0, 4, 0, 3, 0, 2});
  }
  std::vector<h5::Handle> groups;
};

TEST(VtkHdfSource, NewerMajorVersionIsRejected) {
  fs::path p = tsptest::temp_dir() / "v3.hdf";
  {
    Writer w(p);
    w.header({3, 0});
    w.group("/VTKHDF/PointData");
    w.floats("/VTKHDF/PointData/f", {3, 4, 5});
  }
  std::string msg = error_of<FormatError>([&] { open_field(p.string(), "f"); });
  EXPECT_NE(msg.find("version 3.0"), std::string::npos) << msg;
}

TEST(VtkHdfSource, ShapeDisagreeingWithWholeExtentIsRejected) {
  fs::path p = tsptest::temp_dir() / "shape.hdf";
  {
    Writer w(p);
    w.header();
    w.group("/VTKHDF/PointData");
    w.floats("/VTKHDF/PointData/f", {3, 5, 4});  // x and y swapped
  }
  std::string msg = error_of<FormatError>([&] { open_field(p.string(), "f"); });
  EXPECT_NE(msg.find("/VTKHDF/PointData/f"), std::string::npos) << msg;
  EXPECT_NE(msg.find("shape 3x5x4, expected 3x4x5"), std::string::npos) << msg;
}

TEST(VtkHdfSource, TransientArrayWithoutTimeAxisIsRejected) {
  fs::path p = tsptest::temp_dir() / "notime.hdf";
  {
    Writer w(p);
    w.header();
    w.group("/VTKHDF/PointData");
    w.floats("/VTKHDF/PointData/f", {3, 4, 5});
    hid_t steps = w.group("/VTKHDF/Steps");
    w.ints(steps, "NSteps", {2});
  }
  std::string msg = error_of<FormatError>([&] { open_field(p.string(), "f"); });
  EXPECT_NE(msg.find("expected steps x 3x4x5"), std::string::npos) << msg;
}

TEST(VtkHdfSource, OffsetBeyondStoredStepsIsRejected) {
  fs::path p = tsptest::temp_dir() / "offsets.hdf";
  {
    Writer w(p);
    w.header();
    w.group("/VTKHDF/PointData");
    w.floats("/VTKHDF/PointData/f", {2, 3, 4, 5});
    hid_t steps = w.group("/VTKHDF/Steps");
    w.ints(steps, "NSteps", {3});
    w.group("/VTKHDF/Steps/PointDataOffsets");
    w.longs("/VTKHDF/Steps/PointDataOffsets/f", {0, 1, 2});
  }
  std::string msg = error_of<FormatError>([&] { open_field(p.string(), "f"); });
  EXPECT_NE(msg.find("step 2 reads time index 2"), std::string::npos) << msg;
}

TEST(VtkHdfSource, WithoutOffsetsTableStepTReadsIndexT) {
  fs::path p = tsptest::temp_dir() / "nooffsets.hdf";
  {
    Writer w(p);
    w.header();
    w.group("/VTKHDF/PointData");
    w.floats("/VTKHDF/PointData/f", {2, 3, 4, 5});
    hid_t steps = w.group("/VTKHDF/Steps");
    w.ints(steps, "NSteps", {2});
  }
  auto s = open_field(p.string(), "f");
  ASSERT_EQ(s->steps(), 2);
  std::vector<float> v = tsptest::read_step(*s, 1);
  for (float x : v) ASSERT_EQ(x, 1.0f);
}

TEST(VtkHdfSource, MissingNStepsIsRejected) {
  fs::path p = tsptest::temp_dir() / "nsteps.hdf";
  {
    Writer w(p);
    w.header();
    w.group("/VTKHDF/PointData");
    w.floats("/VTKHDF/PointData/f", {2, 3, 4, 5});
    w.group("/VTKHDF/Steps");
  }
  std::string msg = error_of<FormatError>([&] { open_field(p.string(), "f"); });
  EXPECT_NE(msg.find("NSteps"), std::string::npos) << msg;
}

TEST(VtkHdfSource, MissingWholeExtentIsRejected) {
  fs::path p = tsptest::temp_dir() / "extent.hdf";
  {
    Writer w(p);
    w.ints(w.root.get(), "Version", {2, 0});
    w.text(w.root.get(), "Type", "ImageData");
  }
  std::string msg = error_of<FormatError>([&] { open_field(p.string(), ""); });
  EXPECT_NE(msg.find("WholeExtent"), std::string::npos) << msg;
}

TEST(VtkHdfSource, FlatImageStoresTwoDimensionalArrays) {
  // WholeExtent flat in z: VTK stores PointData as (y, x).
  fs::path p = tsptest::temp_dir() / "flat.hdf";
  {
    Writer w(p);
    w.ints(w.root.get(), "Version", {2, 0});
    w.text(w.root.get(), "Type", "ImageData");
    w.ints(w.root.get(), "WholeExtent", {0, 4, 0, 3, 0, 0});
    w.group("/VTKHDF/PointData");
    w.floats("/VTKHDF/PointData/f", {4, 5});
  }
  auto s = open_field(p.string(), "f");
  EXPECT_EQ(s->dims(), (Dims{5, 4, 1}));
  std::vector<float> v = tsptest::read_step(*s, 0);
  for (float x : v) ASSERT_EQ(x, 1.0f);
}

}  // namespace
}  // namespace tsp
