// Several fields of one HDF5 file (build/play --field A,B,C, issue 48): the file is opened and
// walked once whatever the number of fields (1000 names used to open and walk it 1000 times),
// every name is looked up before any field is read, and the missing ones are named. Counted by
// h5::files_opened, never timed.
#include "tsp/voxelize/open_fields.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <string>
#include <vector>

#include "support/paths.h"
#include "tsp/build/build.h"
#include "tsp/core/error.h"
#include "tsp/hdf5/hdf5_handle.h"
#include "tsp/store/tsp_file.h"

namespace tsp {
namespace {

namespace fs = std::filesystem;

constexpr int kFields = 1000;

std::string field_name(int i) { return "f" + std::to_string(i); }

// kFields 3-D datasets of 4³ floats, field i holding i + the sample index.
std::string many_fields_file() {
  const std::string path = (tsptest::temp_dir() / "fields.h5").string();
  hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t shape[3] = {4, 4, 4};
  hid_t space = H5Screate_simple(3, shape, nullptr);
  std::vector<float> v(64);
  for (int i = 0; i < kFields; ++i) {
    for (int s = 0; s < 64; ++s) v[std::size_t(s)] = float(i + s);
    hid_t d = H5Dcreate2(f, field_name(i).c_str(), H5T_NATIVE_FLOAT, space, H5P_DEFAULT,
                         H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(d, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    H5Dclose(d);
  }
  H5Sclose(space);
  H5Fclose(f);
  return path;
}

TEST(OpenFields, AThousandFieldsOfOneHdf5FileOpenItOnce) {
  const std::string path = many_fields_file();
  std::vector<std::string> names;
  for (int i = 0; i < kFields; ++i) names.push_back(field_name(i));
  const std::int64_t before = h5::files_opened();
  const FieldOpener open = open_input_fields(path, {}, {}, names);
  for (int i : {0, 1, 517, kFields - 1}) {
    const auto source = open(field_name(i));
    EXPECT_EQ(source->dims(), (Dims{4, 4, 4}));
    std::vector<float> step(64);
    source->read_step(0, step);
    EXPECT_EQ(step[0], float(i));
    EXPECT_EQ(step[63], float(i + 63));
  }
  EXPECT_EQ(h5::files_opened() - before, 1);

  // All of them built into one file (the cap was 64 names), still one open.
  const std::string out = (tsptest::temp_dir() / "fields.tsp").string();
  BuildOptions o;
  o.brick_size = 4;
  const std::int64_t build_before = h5::files_opened();
  const auto reports = build_tsp_fields(open_input_fields(path, {}, {}, names), names, out, o);
  EXPECT_EQ(h5::files_opened() - build_before, 1);
  ASSERT_EQ(reports.size(), std::size_t(kFields));
  EXPECT_EQ(reports[999].data_range.lo, 999.0);
  EXPECT_EQ(reports[999].data_range.hi, 999.0 + 63);
  EXPECT_EQ(TspFile::open(out)->fields().size(), std::size_t(kFields));
}

TEST(OpenFields, MissingFieldsAreNamedBeforeAnyIsRead) {
  const std::string path = many_fields_file();
  std::vector<std::string> names{"f3", "f7"};
  for (int i = 0; i < kFields - 2; ++i) names.push_back("absent" + std::to_string(i));
  const std::int64_t before = h5::files_opened();
  try {
    open_input_fields(path, {}, {}, names);
    FAIL() << "no error for 998 missing fields";
  } catch (const FormatError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(path + ": 998 of the 1000 fields named not found: 'absent0', 'absent1'"),
              std::string::npos) << m;
    EXPECT_NE(m.find("'absent19' and 978 more; available 3-D/4-D fields: /f0 (4x4x4)"),
              std::string::npos) << m.substr(0, 400);
    EXPECT_EQ(m.find("'absent20'"), std::string::npos);
    EXPECT_EQ(m.find("'f3'"), std::string::npos);
  }
  EXPECT_EQ(h5::files_opened() - before, 1);
}

// --field A,B,C's one split (build and play): every comma splits, one name is no list.
TEST(OpenFields, FieldNamesSplitAtEveryComma) {
  using V = std::vector<std::string>;
  EXPECT_EQ(field_names("U:mag"), V{});
  EXPECT_EQ(field_names(""), V{});
  EXPECT_EQ(field_names("a,b,c"), (V{"a", "b", "c"}));
  EXPECT_EQ(field_names("U:mag,p"), (V{"U:mag", "p"}));
  EXPECT_EQ(field_names("a,,b"), (V{"a", "", "b"}));  // (looked up, reported missing)
  EXPECT_EQ(field_names("a,"), (V{"a", ""}));
  EXPECT_EQ(field_names(","), (V{"", ""}));
}

}  // namespace
}  // namespace tsp
