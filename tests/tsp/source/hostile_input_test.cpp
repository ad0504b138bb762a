// Hostile and broken inputs at the library level, one test per failure found (the files are in
// tests/data/hostile, or made here): every one is a clear, typed error naming the file, never a
// crash, a hang, an allocation of what the file claims, or a lost input.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <vector>

#include "support/memory_source.h"
#include "support/paths.h"
#include "support/reader_formula.h"
#include "tsp/build/build.h"
#include "tsp/core/error.h"
#include "tsp/core/temp_output.h"
#include "tsp/metric/tf_io.h"
#include "tsp/source/open_source.h"

namespace tsp {
namespace {

namespace fs = std::filesystem;
using tsptest::error_of;

std::string hostile(const std::string& name) {
  return (tsptest::test_data_dir() / "hostile" / name).string();
}

std::unique_ptr<VolumeSource> open(const std::string& path) {
  SourceOptions o;
  return open_source(path, o);
}

// Opens path and reads its first step: every error must be a FormatError naming the file.
void expect_format_error(const std::string& path, const std::string& needle) {
  const std::string m = error_of<FormatError>([&] {
    auto s = open(path);
    std::vector<float> v(std::size_t(s->dims().count()));
    s->read_step(0, v);
  });
  EXPECT_NE(m.find(needle), std::string::npos) << path << ": " << m;
  EXPECT_NE(m.find(fs::path(path).filename().string()), std::string::npos) << m;
}

TEST(HostileInput, ZlibHeaderThatWrapsToTheExpectedSizeIsRefused) {
  expect_format_error(hostile("zlib_overflow.vti"), "zlib header describes 3 blocks");
}

TEST(HostileInput, AppendedOffsetsMustBeWholeNonNegativeNumbers) {
  expect_format_error(hostile("offset_negative.vti"), "appended offset \"-1\"");
  expect_format_error(hostile("offset_text.vti"), "appended offset \"abc\"");
}

TEST(HostileInput, HugeExtentIsRefusedBeforeAllocating) {
  expect_format_error(hostile("huge_extent.vti"), "expected every edge in [1, 65536]");
}

TEST(HostileInput, NanTimestepsAreRefused) {
  expect_format_error(hostile("nan_timestep.pvd"), "timestep \"nan\" is not a finite number");
}

// 60,000 nested elements once overflowed the stack of a recursive walk.
TEST(HostileInput, DeeplyNestedXmlDoesNotOverflowTheStack) {
  const auto path = tsptest::temp_dir() / "deep.vti";
  {
    std::ofstream out(path, std::ios::binary);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" "
           "byte_order=\"LittleEndian\" header_type=\"UInt32\">\n<ImageData WholeExtent=\"0 1 0 "
           "0 0 0\"><Piece Extent=\"0 1 0 0 0 0\"><PointData Scalars=\"f\"><DataArray "
           "type=\"Float32\" Name=\"f\" format=\"appended\" offset=\"0\"/></PointData></Piece>"
           "</ImageData>\n";
    for (int i = 0; i < 60000; ++i) out << "<d>";
    for (int i = 0; i < 60000; ++i) out << "</d>";
    const std::uint32_t n = 8;
    const float v[2] = {1.5f, 2.5f};
    out << "\n<AppendedData encoding=\"raw\">_";
    out.write(reinterpret_cast<const char*>(&n), 4);
    out.write(reinterpret_cast<const char*>(v), 8);
    out << "</AppendedData></VTKFile>\n";
  }
  auto s = open(path.string());
  std::vector<float> out(2);
  s->read_step(0, out);
  EXPECT_EQ(out, (std::vector<float>{1.5f, 2.5f}));
}

TEST(HostileInput, NonRegularInputsAreRefusedWithoutOpeningThem) {
  const auto dir = tsptest::temp_dir();
  const auto fifo = (dir / "p.raw").string();
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  // Opening a FIFO for reading would block until a writer comes: the check must not open it.
  auto result = std::async(std::launch::async, [&] {
    SourceOptions o;
    o.raw_dims = Dims{2, 2, 2};
    return error_of<IoError>([&] { open_source(fifo, o); });
  });
  ASSERT_EQ(result.wait_for(std::chrono::seconds(20)), std::future_status::ready)
      << "open_source blocked on a FIFO";
  const std::string m = result.get();
  EXPECT_NE(m.find("is not a regular file"), std::string::npos) << m;
  for (const char* name : {"a.h5", "b.vti", "c.pvd"}) {
    const auto p = (dir / name).string();
    ASSERT_EQ(mkfifo(p.c_str(), 0600), 0);
    auto r = std::async(std::launch::async, [&] { return error_of<IoError>([&] { open(p); }); });
    ASSERT_EQ(r.wait_for(std::chrono::seconds(20)), std::future_status::ready) << name;
    EXPECT_NE(r.get().find("is not a regular file"), std::string::npos) << name;
  }
  fs::create_directory(dir / "d.h5");
  EXPECT_NE(error_of<IoError>([&] { open((dir / "d.h5").string()); }).find("is a directory"),
            std::string::npos);
  EXPECT_NE(error_of<IoError>([&] { open((dir / "none.h5").string()); }).find("does not exist"),
            std::string::npos);
}

TEST(HostileInput, AnOutputThatIsAnInputIsRefusedAndTheInputKept) {
  const auto dir = tsptest::temp_dir();
  for (int t = 0; t < 3; ++t) {
    std::ofstream out(dir / ("u_000" + std::to_string(t) + ".raw"), std::ios::binary);
    const float v[8] = {float(t), 1, 2, 3, 4, 5, 6, 7};
    out.write(reinterpret_cast<const char*>(v), sizeof v);
  }
  fs::create_hard_link(dir / "u_0002.raw", dir / "alias.tsp");
  SourceOptions o;
  o.raw_dims = Dims{2, 2, 2};
  const std::string before = tsptest::read_file(dir / "u_0001.raw");
  for (const char* target : {"u_0001.raw", "alias.tsp"}) {
    auto src = open_source((dir / "u_%04d.raw").string(), o);
    const std::string m = error_of<UsageError>(
        [&] { build_tsp_file(*src, (dir / target).string(), BuildOptions{}); });
    EXPECT_NE(m.find("the output is the input file"), std::string::npos) << m;
  }
  EXPECT_EQ(tsptest::read_file(dir / "u_0001.raw"), before);
  EXPECT_EQ(fs::file_size(dir / "u_0002.raw"), 32u);
}

TEST(HostileInput, HugeHdf5AndVtkhdfSizesAreRefusedBeforeAllocating) {
  const auto dir = tsptest::temp_dir();
  // A 4-D dataset of 10^5 steps of 10^5 × 10^5 × 10^5 samples: chunked, nothing written.
  const auto big = (dir / "big.h5").string();
  {
    hid_t f = H5Fcreate(big.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    hsize_t dims[4] = {100000, 100000, 100000, 100000}, chunk[4] = {1, 1, 16, 16};
    hid_t space = H5Screate_simple(4, dims, nullptr);
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 4, chunk);
    hid_t ds = H5Dcreate2(f, "v", H5T_NATIVE_FLOAT, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    ASSERT_GE(ds, 0);
    H5Dclose(ds);
    H5Pclose(dcpl);
    H5Sclose(space);
    H5Fclose(f);
  }
  EXPECT_NE(error_of<FormatError>([&] { open(big); }).find("expected every edge"),
            std::string::npos);
  // VTKHDF with NSteps = INT_MAX.
  const auto vtkhdf = dir / "t.hdf";
  fs::copy_file(tsptest::test_data_dir() / "h5" / "vtkhdf_transient.hdf", vtkhdf);
  {
    hid_t f = H5Fopen(vtkhdf.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t g = H5Gopen2(f, "/VTKHDF/Steps", H5P_DEFAULT);
    hid_t a = H5Aopen(g, "NSteps", H5P_DEFAULT);
    const long long n = 2147483647;
    ASSERT_GE(H5Awrite(a, H5T_NATIVE_LLONG, &n), 0);
    H5Aclose(a);
    H5Gclose(g);
    H5Fclose(f);
  }
  const std::string m = error_of<FormatError>([&] { open(vtkhdf.string()); });
  EXPECT_NE(m.find("2147483647 time steps"), std::string::npos) << m;
}

TEST(HostileInput, TransferFunctionNumbersBeyondDoubleAreFormatErrors) {
  for (const char* name : {"tf_1e400.json", "tf_inf_domain.json"}) {
    const std::string m = error_of<FormatError>([&] { load_transfer_function(hostile(name)); });
    EXPECT_NE(m.find(name), std::string::npos) << m;
  }
}

TEST(HostileInput, ConstantFieldsGetAPresetDomainTheyRenderIn) {
  EXPECT_EQ(preset_domain({2, 5}), (ValueRange{2, 5}));
  const ValueRange c = preset_domain({7, 7});
  EXPECT_LT(c.lo, 7);
  EXPECT_GT(c.hi, 7);
  EXPECT_DOUBLE_EQ(0.5 * (c.lo + c.hi), 7);
  EXPECT_EQ(preset_domain({NAN, 1}), (ValueRange{0, 1}));
  EXPECT_NO_THROW(transfer_function_from_arg("preset:filled", {3, 3}));
}

// A temporary whose writer died (no lock) is removed by the next writer of the same name; one
// whose writer is alive (locked) is kept.
TEST(HostileInput, StaleTemporariesOfTheSameOutputAreRemoved) {
  const auto dir = tsptest::temp_dir();
  const auto out = (dir / "run.tsp").string();
  std::ofstream(dir / ".run.tsp.tmp-AbC123") << "left by a killed build";
  std::ofstream(dir / ".other.tsp.tmp-AbC123") << "another output's";
  const auto live = dir / ".run.tsp.tmp-Live42";
  std::ofstream(live) << "a running build's";
  const int fd = ::open(live.c_str(), O_RDWR);
  ASSERT_GE(fd, 0);
  struct flock fl {};
  fl.l_type = F_WRLCK;
  ASSERT_EQ(fcntl(fd, F_OFD_SETLK, &fl), 0);
  write_file_atomically(out, "done\n");
  EXPECT_FALSE(fs::exists(dir / ".run.tsp.tmp-AbC123"));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(dir / ".other.tsp.tmp-AbC123"));
  ::close(fd);  // the "writer" dies: now it is stale
  EXPECT_EQ(remove_stale_temporaries(out), 1);
  EXPECT_FALSE(fs::exists(live));
  EXPECT_EQ(tsptest::read_file(out), "done\n");
}

}  // namespace
}  // namespace tsp
