#include "tsp/source/hdf5_source.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "support/paths.h"
#include "support/reader_formula.h"
#include "tsp/core/error.h"

namespace tsp {
namespace {

namespace fs = std::filesystem;
using namespace tsptest;  // the reader fixtures' formula, grids and helpers

TEST(Hdf5Source, FourDDatasetGivesOneStepPerLeadingIndex) {
  auto s = open_field(h5_fixture("grid4d.h5"), "f");
  expect_steps(*s, kFixtureDims, {0, 1, 2});
  EXPECT_NE(s->describe().find("/f"), std::string::npos);
}

TEST(Hdf5Source, EmptyFieldPicksTheOnlyFourDDataset) {
  expect_steps(*open_field(h5_fixture("grid4d.h5"), ""), kFixtureDims, {0, 1, 2});
}

TEST(Hdf5Source, ThreeDDatasetIsOneStepByBareNameOrPath) {
  auto s = open_field(h5_fixture("grid4d.h5"), "single");
  expect_steps(*s, kFixtureDims, {0});
  expect_steps(*open_field(h5_fixture("grid4d.h5"), "/grp/d"), kFixtureDims, {2});
}

TEST(Hdf5Source, GroupOfStepsReadsInNaturalNameOrder) {
  auto s = open_field(h5_fixture("group_steps.h5"), "steps");
  // t1, t2, t10: the datasets hold f at t = their number
  expect_steps(*s, kFixtureDims, {1, 2, 10});
}

TEST(Hdf5Source, GroupWithStepsOfDifferentShapesIsRejected) {
  std::string msg =
      error_of<FormatError>([] { open_field(h5_fixture("group_steps.h5"), "/mixed"); });
  EXPECT_NE(msg.find("group_steps.h5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("/mixed/a1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("3x4x6"), std::string::npos) << msg;
  EXPECT_NE(msg.find("3x4x5"), std::string::npos) << msg;
}

TEST(Hdf5Source, IntegerDatasetsConvertToFloat) {
  for (const char* field : {"plain", "u64"}) {
    auto s = open_field(h5_fixture("int16.h5"), field);
    SCOPED_TRACE(field);
    expect_steps(*s, kFixtureDims, {0, 1, 2});
  }
}

TEST(Hdf5Source, NetcdfPackingAppliesScaleOffsetAndMapsFillToNaN) {
  // Stored 2·f with scale_factor 0.5 and add_offset 100: values f + 100, except the sample set
  // to _FillValue (step 1, x=y=z=0) and the one set to missing_value (step 2, x=3 y=2 z=1).
  auto s = open_field(h5_fixture("int16.h5"), "packed");
  ASSERT_EQ(s->steps(), 3);
  expect_formula(tsptest::read_step(*s, 0), kFixtureDims, 0, 100);
  std::vector<float> s1 = tsptest::read_step(*s, 1);
  EXPECT_TRUE(std::isnan(s1[0]));
  s1[0] = tsptest::formula(0, 0, 0, 1) + 100;
  expect_formula(s1, kFixtureDims, 1, 100);
  std::vector<float> s2 = tsptest::read_step(*s, 2);
  const std::size_t i = std::size_t((1 * 4 + 2) * 5 + 3);
  EXPECT_TRUE(std::isnan(s2[i]));
  s2[i] = tsptest::formula(3, 2, 1, 2) + 100;
  expect_formula(s2, kFixtureDims, 2, 100);
}

TEST(Hdf5Source, NonNumericTypesAreFormatErrors) {
  std::string msg = error_of<FormatError>([] { open_field(h5_fixture("bad_types.h5"), "text"); });
  EXPECT_NE(msg.find("bad_types.h5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("/text"), std::string::npos) << msg;
  EXPECT_NE(msg.find("string"), std::string::npos) << msg;
  msg = error_of<FormatError>([] { open_field(h5_fixture("bad_types.h5"), "compound"); });
  EXPECT_NE(msg.find("compound"), std::string::npos) << msg;
}

TEST(Hdf5Source, WrongRankNamesShapeAndExpectation) {
  std::string msg = error_of<FormatError>([] { open_field(h5_fixture("grid4d.h5"), "plane"); });
  EXPECT_NE(msg.find("/plane"), std::string::npos) << msg;
  EXPECT_NE(msg.find("rank 2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("4x5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected 3-D"), std::string::npos) << msg;
}

// A 3-D dataset whose first dimension is time (NetCDF-4's scale named Time, as WRF's T2, HGT,
// PSFC): a 2-D field over time is refused by name and shape, marked among the candidates, and
// not taken as the default; a plain 3-D dataset (no time dimension) is still one volume.
TEST(Hdf5Source, TwoDFieldsOverTimeAreRefusedAndMarked) {
  const std::string file = h5_fixture("map_over_time.nc");
  const std::string msg = error_of<FormatError>([&] { open_field(file, "T2"); });
  EXPECT_NE(msg.find("/T2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("2-D field over time (Time 3 x south_north 4 x west_east 5)"), std::string::npos)
      << msg;
  EXPECT_NE(msg.find("this file's: /T (3x2x4x5), /slab (3x4x5)"), std::string::npos) << msg;
  // Listed as candidates (a misspelt field), the map is marked.
  const std::string any = error_of<FormatError>([&] { open_field(file, "T3"); });
  EXPECT_NE(any.find("/T2 (3x4x5, 2-D over time: not playable)"), std::string::npos) << any;
  // Without --field the only 4-D dataset is the default; the slab and the map are not counted.
  auto s = open_field(file, "");
  EXPECT_EQ(s->steps(), 3);
  EXPECT_EQ(s->dims(), (Dims{5, 4, 2}));
  auto slab = open_field(file, "slab");
  EXPECT_EQ(slab->steps(), 1);
  EXPECT_EQ(slab->dims(), (Dims{5, 4, 3}));
  // The real WRF output's T2 (4 times of 48 x 48), which built as 48x48x4 voxels before.
  const auto wrf = katrina_file();
  if (!fs::exists(wrf)) GTEST_SKIP() << "shared data absent: " << wrf;
  const std::string w = error_of<FormatError>([&] { open_field(wrf.string(), "T2"); });
  EXPECT_NE(w.find("(Time 4 x south_north 48 x west_east 48)"), std::string::npos) << w;
}

TEST(Hdf5Source, NonNumericPackingAttributeIsAFormatError) {
  std::string msg =
      error_of<FormatError>([] { open_field(h5_fixture("bad_types.h5"), "bad_scale"); });
  EXPECT_NE(msg.find("scale_factor"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected a number"), std::string::npos) << msg;
}

TEST(Hdf5Source, MissingFieldListsTheAvailableFields) {
  std::string msg = error_of<FormatError>([] { open_field(h5_fixture("grid4d.h5"), "nope"); });
  EXPECT_NE(msg.find("grid4d.h5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'nope'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("/f (3x3x4x5)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("/grp/d (3x4x5)"), std::string::npos) << msg;
  EXPECT_EQ(msg.find("/time"), std::string::npos) << msg;  // 1-D: not a candidate
}

TEST(Hdf5Source, EmptyFieldWithSeveralFourDDatasetsListsThem) {
  std::string msg = error_of<FormatError>([] { open_field(h5_fixture("int16.h5"), ""); });
  for (const char* name : {"/plain", "/packed", "/u64"})
    EXPECT_NE(msg.find(name), std::string::npos) << msg;
}

TEST(Hdf5Source, TruncatedFileIsAnErrorNotACrash) {
  fs::path dir = tsptest::temp_dir();
  std::ifstream in(h5_fixture("grid4d.h5"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (std::size_t keep : {bytes.size() / 2, std::size_t(600), std::size_t(100)}) {
    fs::path p = dir / ("cut" + std::to_string(keep) + ".h5");
    std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(keep));
    EXPECT_THROW(
        {
          auto s = open_field(p.string(), "f");
          for (int t = 0; t < s->steps(); ++t) tsptest::read_step(*s, t);
        },
        FormatError)
        << keep;
  }
}

TEST(Hdf5Source, NonHdf5FileWithHdf5ExtensionIsAFormatError) {
  fs::path p = tsptest::temp_dir() / "fake.h5";
  std::ofstream(p) << "just text\n";
  std::string msg = error_of<FormatError>([&] { open_field(p.string(), "f"); });
  EXPECT_NE(msg.find("fake.h5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not an HDF5 file"), std::string::npos) << msg;
}

TEST(Hdf5Source, NetcdfClassicFileIsNamedAsSuch) {
  fs::path p = tsptest::temp_dir() / "classic.nc";
  std::ofstream(p, std::ios::binary) << std::string("CDF\x01\0\0\0\0", 8);
  std::string msg = error_of<FormatError>([&] { open_field(p.string(), "T"); });
  EXPECT_NE(msg.find("NetCDF classic"), std::string::npos) << msg;
}

TEST(Hdf5Source, MissingFileIsAnIoError) {
  std::string msg = error_of<IoError>([] { open_field(h5_fixture("absent.h5"), "f"); });
  EXPECT_NE(msg.find("absent.h5"), std::string::npos) << msg;
}

TEST(Hdf5Source, HdfSignatureIsDetectedWhateverTheExtension) {
  fs::path p = tsptest::temp_dir() / "grid.data";
  fs::copy_file(h5_fixture("grid4d.h5"), p);
  auto s = open_field(p.string(), "f");
  EXPECT_EQ(s->steps(), 3);
}

// The real WRF (NetCDF-4) file: 4 steps of 14 × 48 × 48, float32.

// A WRF field with its levels as stored (--vertical-levels native): the h5dump values below.
std::unique_ptr<VolumeSource> open_native(const std::string& path, const std::string& field) {
  SourceOptions o;
  o.field = field;
  o.vertical.mode = VerticalLevels::Mode::native;
  return open_source(path, o);
}

float at(const std::vector<float>& v, int x, int y, int z) {
  return v[std::size_t((z * 48 + y) * 48 + x)];
}

TEST(Hdf5Source, WrfTemperatureMatchesH5dump) {
  if (!fs::exists(katrina_file())) GTEST_SKIP() << "shared data absent: " << katrina_file();
  auto s = open_native(katrina_file().string(), "T");
  EXPECT_EQ(s->dims(), (Dims{48, 48, 14}));
  ASSERT_EQ(s->steps(), 4);
  // Reference values printed by `h5dump -d /T -s "t,z,y,x" -c "1,1,1,1" ci_test_file.nc`
  // (6 significant digits), indices (t, z, y, x).
  struct Sample {
    int t, z, y, x;
    float value;
  };
  for (Sample smp : {Sample{0, 0, 0, 0, 1.27993f}, Sample{3, 13, 47, 47, 42.4775f},
                     Sample{1, 5, 20, 30, 3.92902f}, Sample{2, 7, 10, 40, 7.95246f}}) {
    std::vector<float> v = tsptest::read_step(*s, smp.t);
    EXPECT_NEAR(at(v, smp.x, smp.y, smp.z), smp.value, 1e-5 * std::fabs(smp.value) + 1e-6)
        << smp.t << "," << smp.z << "," << smp.y << "," << smp.x;
  }
}

TEST(Hdf5Source, WrfCloudWaterMatchesH5dump) {
  if (!fs::exists(katrina_file())) GTEST_SKIP() << "shared data absent: " << katrina_file();
  auto s = open_native(katrina_file().string(), "/QCLOUD");
  EXPECT_EQ(s->dims(), (Dims{48, 48, 14}));
  ASSERT_EQ(s->steps(), 4);
  // From `h5dump -d /QCLOUD -s "t,z,y,x" -c "1,1,1,1" ci_test_file.nc`.
  struct Sample {
    int t, z, y, x;
    float value;
  };
  for (Sample smp : {Sample{0, 9, 43, 43, 0.00181097f}, Sample{1, 5, 45, 43, 0.000562077f},
                     Sample{2, 7, 46, 41, 0.000880334f}, Sample{3, 6, 46, 39, 0.000532236f},
                     Sample{1, 5, 20, 30, 0.0f}}) {
    std::vector<float> v = tsptest::read_step(*s, smp.t);
    EXPECT_NEAR(at(v, smp.x, smp.y, smp.z), smp.value, 1e-5 * std::fabs(smp.value) + 1e-12)
        << smp.t << "," << smp.z << "," << smp.y << "," << smp.x;
  }
}

// WRF has no coordinate variables: the grid's spacing comes from the global DX and DY (10 km
// here, `h5dump -a DX`) and, with the levels as stored, the mean layer thickness of the geopotential (PH + PHB)/g at the first
// step — computed here over the whole arrays as an independent check.
TEST(Hdf5Source, WrfSpacingFromDxDyAndTheGeopotential) {
  if (!fs::exists(katrina_file())) GTEST_SKIP() << "shared data absent: " << katrina_file();
  hid_t f = H5Fopen(katrina_file().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  std::vector<float> ph(4 * 15 * 48 * 48), phb(ph.size());
  for (auto [name, v] : {std::pair{"PH", &ph}, std::pair{"PHB", &phb}}) {
    hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
    ASSERT_GE(H5Dread(d, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v->data()), 0);
    H5Dclose(d);
  }
  H5Fclose(f);
  auto mean_height = [&](int level) {  // step 0
    double sum = 0;
    for (int i = 0; i < 48 * 48; ++i) {
      const std::size_t k = std::size_t(level) * 48 * 48 + std::size_t(i);
      sum += double(ph[k]) + double(phb[k]);
    }
    return sum / (48 * 48) / 9.81;
  };
  const double dz = (mean_height(14) - mean_height(0)) / 14;
  // Mass points (T: 14 levels), staggered vertically (W: 15) and horizontally (U: 49 wide in x,
  // V in y: half a cell, 5 km, before the first mass point).
  for (const char* field : {"T", "W", "U", "V"}) {
    auto s = open_native(katrina_file().string(), field);
    EXPECT_DOUBLE_EQ(s->origin()[0], s->dims().x == 49 ? -5000.0 : 0.0) << field;
    EXPECT_DOUBLE_EQ(s->origin()[1], s->dims().y == 49 ? -5000.0 : 0.0) << field;
    EXPECT_DOUBLE_EQ(s->spacing()[0], 10000.0);
    EXPECT_DOUBLE_EQ(s->spacing()[1], 10000.0);
    EXPECT_NEAR(s->spacing()[2], dz, 1e-9 * dz) << field;
    const double first = mean_height(0) + (s->dims().z == 14 ? 0.5 * dz : 0.0);
    EXPECT_NEAR(s->origin()[2], first, 1e-9 * first) << field;
  }
}

TEST(Hdf5Source, WrfWithoutFieldListsItsVariables) {
  if (!fs::exists(katrina_file())) GTEST_SKIP() << "shared data absent: " << katrina_file();
  std::string msg = error_of<FormatError>([] { open_field(katrina_file().string(), ""); });
  EXPECT_NE(msg.find("/T (4x14x48x48)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("/QCLOUD"), std::string::npos) << msg;
  EXPECT_NE(msg.find("--field"), std::string::npos) << msg;
}

}  // namespace
}  // namespace tsp
