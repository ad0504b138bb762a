#include "tsp/source/hdf5_writer.h"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <vector>

#include "support/paths.h"
#include "tsp/core/error.h"
#include "tsp/hdf5/hdf5_handle.h"
#include "tsp/source/procedural/generate.h"

namespace tsp {
namespace {

namespace fs = std::filesystem;

// v = x + 10·y + 100·z + 1000·t: every sample distinct and checkable by formula.
class RampSource : public VolumeSource {
 public:
  RampSource(Dims d, int steps, int fail_at = -1) : d_(d), steps_(steps), fail_at_(fail_at) {}
  Dims dims() const override { return d_; }
  int steps() const override { return steps_; }
  std::string describe() const override { return "ramp test source"; }
  void read_step(int t, std::span<float> out) override {
    if (t == fail_at_) throw FormatError("ramp: step " + std::to_string(t) + " is corrupt");
    std::size_t n = 0;
    for (int z = 0; z < d_.z; ++z)
      for (int y = 0; y < d_.y; ++y)
        for (int x = 0; x < d_.x; ++x) out[n++] = float(ramp(x, y, z, t));
  }
  static double ramp(int x, int y, int z, int t) { return x + 10.0 * y + 100.0 * z + 1000.0 * t; }

 private:
  Dims d_;
  int steps_;
  int fail_at_;
};

Hdf5WriteOptions named(const std::string& dataset) {
  Hdf5WriteOptions o;
  o.dataset = dataset;
  return o;
}

std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

h5::Handle open_dataset(const fs::path& file, const std::string& name, h5::Handle& f) {
  f = h5::open_file_readonly(file.string());
  h5::Handle d(H5Dopen2(f.get(), name.c_str(), H5P_DEFAULT));
  EXPECT_TRUE(d) << name;
  return d;
}

std::int64_t read_int_attr(hid_t obj, const char* name) {
  h5::Handle a(H5Aopen(obj, name, H5P_DEFAULT));
  EXPECT_TRUE(a) << name;
  std::int64_t v = -1;
  EXPECT_GE(H5Aread(a.get(), H5T_NATIVE_INT64, &v), 0) << name;
  return v;
}

std::string read_string_attr(hid_t obj, const char* name) {
  h5::Handle a(H5Aopen(obj, name, H5P_DEFAULT));
  EXPECT_TRUE(a) << name;
  h5::Handle type(H5Aget_type(a.get()));
  EXPECT_EQ(H5Tget_class(type.get()), H5T_STRING);
  EXPECT_FALSE(H5Tis_variable_str(type.get()));
  std::string s(H5Tget_size(type.get()), '\0');
  EXPECT_GE(H5Aread(a.get(), type.get(), s.data()), 0);
  return s.substr(0, s.find('\0'));
}

std::vector<float> read_all(hid_t dset) {
  auto shape = h5::dataset_shape(dset);
  std::size_t n = 1;
  for (auto s : shape) n *= s;
  std::vector<float> v(n);
  EXPECT_GE(H5Dread(dset, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
  return v;
}

std::vector<hsize_t> chunk_of(hid_t dset) {
  h5::Handle plist(H5Dget_create_plist(dset));
  std::vector<hsize_t> c(4, 0);
  EXPECT_EQ(H5Pget_chunk(plist.get(), 4, c.data()), 4);
  return c;
}

TEST(Hdf5Writer, WritesShapeValuesTypeAndAttributes) {
  const fs::path dir = tsptest::temp_dir(), out = dir / "ramp.h5";
  RampSource src(Dims{5, 4, 3}, 3);
  Hdf5WriteOptions o = named("ramp");
  o.attributes = {{"generator", std::string("ramp")},
                  {"seed", std::uint64_t(1) << 63},
                  {"generator_version", std::int64_t(4)},
                  {"scale", 2.5},
                  {"levels", std::vector<std::int64_t>{-1, 7}}};
  write_hdf5(src, out, o);

  h5::Handle f;
  h5::Handle d = open_dataset(out, "/ramp", f);
  EXPECT_EQ(h5::dataset_shape(d.get()), (std::vector<hsize_t>{3, 3, 4, 5}));
  h5::Handle type(H5Dget_type(d.get()));
  EXPECT_GT(H5Tequal(type.get(), H5T_IEEE_F32LE), 0);
  std::vector<float> v = read_all(d.get());
  std::size_t n = 0;
  for (int t = 0; t < 3; ++t)
    for (int z = 0; z < 3; ++z)
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x)
          ASSERT_EQ(v[n++], float(RampSource::ramp(x, y, z, t))) << x << y << z << t;

  h5::Handle dims_attr(H5Aopen(d.get(), "dims", H5P_DEFAULT));
  ASSERT_TRUE(dims_attr);
  std::int64_t dims[3] = {0, 0, 0};
  ASSERT_GE(H5Aread(dims_attr.get(), H5T_NATIVE_INT64, dims), 0);
  EXPECT_EQ(dims[0], 5);
  EXPECT_EQ(dims[1], 4);
  EXPECT_EQ(dims[2], 3);
  EXPECT_EQ(read_int_attr(d.get(), "steps"), 3);
  EXPECT_EQ(read_string_attr(d.get(), "axes"), "t,z,y,x");
  EXPECT_EQ(read_string_attr(d.get(), "source"), "ramp test source");
  EXPECT_EQ(read_string_attr(d.get(), "generator"), "ramp");
  EXPECT_EQ(read_int_attr(d.get(), "generator_version"), 4);
  {
    h5::Handle a(H5Aopen(d.get(), "seed", H5P_DEFAULT));
    std::uint64_t seed = 0;
    ASSERT_GE(H5Aread(a.get(), H5T_NATIVE_UINT64, &seed), 0);
    EXPECT_EQ(seed, std::uint64_t(1) << 63);
    h5::Handle s(H5Aopen(d.get(), "scale", H5P_DEFAULT));
    double scale = 0;
    ASSERT_GE(H5Aread(s.get(), H5T_NATIVE_DOUBLE, &scale), 0);
    EXPECT_EQ(scale, 2.5);
    h5::Handle l(H5Aopen(d.get(), "levels", H5P_DEFAULT));
    std::int64_t levels[2] = {0, 0};
    ASSERT_GE(H5Aread(l.get(), H5T_NATIVE_INT64, levels), 0);
    EXPECT_EQ(levels[0], -1);
    EXPECT_EQ(levels[1], 7);
  }
  // Small steps are one chunk each.
  EXPECT_EQ(chunk_of(d.get()), (std::vector<hsize_t>{1, 3, 4, 5}));
  EXPECT_EQ(listing(dir), std::vector<std::string>{"ramp.h5"});
}

TEST(Hdf5Writer, LargeStepsAreChunkedInSlabsOfWholeZSlices) {
  // One z-slice is 512·512·4 B = 1 MiB, so a 4 MiB chunk holds 4 slices.
  const fs::path out = tsptest::temp_dir() / "big.h5";
  RampSource src(Dims{512, 512, 6}, 1);
  write_hdf5(src, out, named("big"));
  h5::Handle f;
  h5::Handle d = open_dataset(out, "big", f);
  EXPECT_EQ(chunk_of(d.get()), (std::vector<hsize_t>{1, 4, 512, 512}));
  std::vector<float> v = read_all(d.get());
  EXPECT_EQ(v[(std::size_t(5) * 512 + 511) * 512 + 3], float(RampSource::ramp(3, 511, 5, 0)));
}

TEST(Hdf5Writer, GzipCompressesAndReadsBackExactly) {
  const fs::path dir = tsptest::temp_dir();
  GenerateOptions g;
  g.dims = Dims{24, 24, 24};
  g.steps = 3;
  auto gen = make_generated_source("shock", g);
  Hdf5WriteOptions o = named("shock");
  o.gzip_level = 6;
  write_hdf5(*gen, dir / "z.h5", o);
  write_hdf5(*gen, dir / "raw.h5", named("shock"));
  EXPECT_LT(fs::file_size(dir / "z.h5"), fs::file_size(dir / "raw.h5"));
  h5::Handle f;
  h5::Handle d = open_dataset(dir / "z.h5", "shock", f);
  h5::Handle plist(H5Dget_create_plist(d.get()));
  EXPECT_EQ(H5Pget_nfilters(plist.get()), 2);  // shuffle + deflate
  std::vector<float> v = read_all(d.get()), step(std::size_t(g.dims->count()));
  for (int t = 0; t < 3; ++t) {
    gen->read_step(t, step);
    for (std::size_t i = 0; i < step.size(); ++i)
      ASSERT_EQ(v[t * step.size() + i], step[i]) << t << " " << i;
  }
}

TEST(Hdf5Writer, ReplacesAnExistingFile) {
  const fs::path dir = tsptest::temp_dir(), out = dir / "a.h5";
  { std::ofstream(out) << "old contents"; }
  RampSource src(Dims{2, 2, 2}, 2);
  write_hdf5(src, out, named("ramp"));
  h5::Handle f;
  h5::Handle d = open_dataset(out, "ramp", f);
  EXPECT_EQ(h5::dataset_shape(d.get()), (std::vector<hsize_t>{2, 2, 2, 2}));
  EXPECT_EQ(listing(dir), std::vector<std::string>{"a.h5"});
}

TEST(Hdf5Writer, SourceErrorLeavesNoTempFileAndKeepsTheOldOutput) {
  const fs::path dir = tsptest::temp_dir(), out = dir / "a.h5";
  { std::ofstream(out) << "old contents"; }
  RampSource src(Dims{4, 4, 4}, 5, /*fail_at=*/3);
  EXPECT_THROW(write_hdf5(src, out, named("ramp")), FormatError);
  EXPECT_EQ(listing(dir), std::vector<std::string>{"a.h5"});
  std::ifstream in(out);
  std::string s;
  std::getline(in, s);
  EXPECT_EQ(s, "old contents");
}

TEST(Hdf5Writer, UnwritableOrMissingDirectoryIsIoError) {
  const fs::path dir = tsptest::temp_dir();
  RampSource src(Dims{2, 2, 2}, 1);
  // Root ignores permission bits, so a read-only directory only stops non-root users; /proc
  // refuses new files to everyone.
  fs::path locked = dir / "locked";
  fs::create_directory(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
  const fs::path unwritable = geteuid() == 0 ? fs::path("/proc") : locked;
  try {
    write_hdf5(src, unwritable / "x.h5", named("ramp"));
    FAIL() << "no throw";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("x.h5"), std::string::npos) << e.what();
  }
  fs::permissions(locked, fs::perms::owner_all);
  EXPECT_TRUE(listing(locked).empty());

  EXPECT_THROW(write_hdf5(src, dir / "missing" / "x.h5", named("ramp")), IoError);
  { std::ofstream(dir / "file") << "x"; }
  EXPECT_THROW(write_hdf5(src, dir / "file" / "x.h5", named("ramp")), IoError);
  fs::create_directory(dir / "adir");
  EXPECT_THROW(write_hdf5(src, dir / "adir", named("ramp")), IoError);
  EXPECT_EQ(listing(dir), (std::vector<std::string>{"adir", "file", "locked"}));
}

TEST(Hdf5Writer, BadOptionsAreUsageErrors) {
  const fs::path dir = tsptest::temp_dir();
  RampSource src(Dims{2, 2, 2}, 1);
  for (std::string bad : {"", "a/b", "/a", ".", ".."})
    EXPECT_THROW(write_hdf5(src, dir / "x.h5", named(bad)), UsageError) << bad;
  Hdf5WriteOptions o = named("ok");
  o.gzip_level = 10;
  EXPECT_THROW(write_hdf5(src, dir / "x.h5", o), UsageError);
  o.gzip_level = -1;
  EXPECT_THROW(write_hdf5(src, dir / "x.h5", o), UsageError);
  o = named("ok");
  o.attributes = {{"dims", std::int64_t(1)}};
  EXPECT_THROW(write_hdf5(src, dir / "x.h5", o), UsageError);
  o.attributes = {{"a", std::int64_t(1)}, {"a", std::int64_t(2)}};
  EXPECT_THROW(write_hdf5(src, dir / "x.h5", o), UsageError);
  EXPECT_TRUE(listing(dir).empty());
}

}  // namespace
}  // namespace tsp
