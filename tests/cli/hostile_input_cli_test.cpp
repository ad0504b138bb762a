// Issue 28, inputs: every path a command opens — named on the command line or found inside
// another file (a .vtm block, a series entry, a script, a diff input, HDF5 external storage and
// external links) — passes one gate: a FIFO or a device is refused at once (never a hang, never
// an endless read), and HDF5 files may read other files only with --allow-external. Costs out
// of proportion to the file end with a clear error, and garbage that exited 0 is refused.
// Commands run under `timeout` so that a regression (a hang, ten minutes of voxelizing) fails
// the test with exit 124 instead of blocking the suite; no test asserts a duration.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "support/paths.h"
#include "support/vtu_text.h"

namespace {

namespace fs = std::filesystem;
using tsptest::quote;

// Far longer than any of these commands takes, far shorter than a hang or the old costs.
const std::string kGuard = "timeout 120 ";

tsptest::RunResult run(const std::string& args) {
  return tsptest::run_command(kGuard + quote(tsptest::tspplay_bin()) + " " + args);
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A .vtu of `copies` hexahedra that all use the same 8 points (the unit cube, or with flat the
// unit square at z = 0).
void write_hex_copies(const fs::path& path, int copies, bool flat = false) {
  std::ofstream out(path);
  out << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">"
         "<UnstructuredGrid><Piece NumberOfPoints=\"8\" NumberOfCells=\""
      << copies << "\"><PointData><DataArray type=\"Float32\" Name=\"f\" format=\"ascii\">"
      << "0 1 2 3 4 5 6 7</DataArray></PointData><Points><DataArray type=\"Float32\" "
         "NumberOfComponents=\"3\" format=\"ascii\">";
  const double z = flat ? 0 : 1;
  out << "0 0 0 1 0 0 1 1 0 0 1 0 0 0 " << z << " 1 0 " << z << " 1 1 " << z << " 0 1 " << z;
  out << "</DataArray></Points><Cells><DataArray type=\"Int32\" Name=\"connectivity\" "
         "format=\"ascii\">";
  for (int c = 0; c < copies; ++c) out << "0 1 2 3 4 5 6 7\n";
  out << "</DataArray><DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">";
  for (int c = 1; c <= copies; ++c) out << 8 * c << "\n";
  out << "</DataArray><DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">";
  for (int c = 0; c < copies; ++c) out << "12\n";
  out << "</DataArray></Cells></Piece></UnstructuredGrid></VTKFile>";
}

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

std::string vtm_naming(const std::string& block) {
  return "<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\"><vtkMultiBlockDataSet>"
         "<DataSet name=\"internal\" file=\"" + block + "\"/></vtkMultiBlockDataSet></VTKFile>";
}

// The 2 steps of 4x4x4 float32 samples the HDF5 tests store: step t, sample i holds t * 100 + i.
constexpr int kSteps = 2, kEdge = 4, kSamples = kSteps * kEdge * kEdge * kEdge;
std::vector<float> sample_values() {
  std::vector<float> v(kSamples);
  for (int i = 0; i < kSamples; ++i) v[std::size_t(i)] = float(i / 64 * 100 + i % 64);
  return v;
}

// Writes path with a 4-D float32 dataset /f whose raw bytes are stored in the file `external`
// (HDF5 external storage, H5Pset_external).
void write_external_storage_h5(const fs::path& path, const std::string& external) {
  const hsize_t dims[4] = {kSteps, kEdge, kEdge, kEdge};
  hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hid_t space = H5Screate_simple(4, dims, nullptr);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_external(dcpl, external.c_str(), 0, hsize_t(kSamples) * sizeof(float));
  hid_t ds = H5Dcreate2(file, "f", H5T_IEEE_F32LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  H5Dclose(ds);
  H5Pclose(dcpl);
  H5Sclose(space);
  H5Fclose(file);
}

// Writes path with /f an external link to target's /f, and target with that dataset.
void write_external_link_h5(const fs::path& path, const fs::path& target) {
  const hsize_t dims[4] = {kSteps, kEdge, kEdge, kEdge};
  const std::vector<float> v = sample_values();
  hid_t t = H5Fcreate(target.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hid_t space = H5Screate_simple(4, dims, nullptr);
  hid_t ds = H5Dcreate2(t, "f", H5T_IEEE_F32LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(ds, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Dclose(ds);
  H5Sclose(space);
  H5Fclose(t);
  hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  H5Lcreate_external(target.c_str(), "/f", f, "f", H5P_DEFAULT, H5P_DEFAULT);
  H5Fclose(f);
}

// A FIFO at dir/name.
fs::path fifo(const fs::path& dir, const std::string& name) {
  const fs::path p = dir / name;
  EXPECT_EQ(mkfifo(p.c_str(), 0600), 0);
  return p;
}

TEST(HostileInputCli, FifoOrDeviceAsAVtmBlockIsRefusedAtOnce) {
  const fs::path dir = tsptest::temp_dir();
  for (const std::string block : {fifo(dir, "pipe.vtu").string(), std::string("/dev/zero")}) {
    write_text(dir / "case.vtm", vtm_naming(block));
    auto r = run("build " + quote(dir / "case.vtm") + " -o " + quote(dir / "o.tsp"));
    EXPECT_EQ(r.exit_code, 1) << block << ": " << r.err;
    EXPECT_TRUE(has(r.err, "case.vtm") && has(r.err, block) &&
                has(r.err, "is not a regular file"))
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "o.tsp"));
  }
}

TEST(HostileInputCli, FifoOrDeviceInASeriesIsRefusedAtOnce) {
  const fs::path dir = tsptest::temp_dir();
  write_text(dir / "pipe.vtm", vtm_naming(fifo(dir, "pipe.vtu").string()));
  write_text(dir / "ok.vtu", tsptest::kOneTetVtu);
  // A .vtm.series whose second step's block is a FIFO, a .vtu.series naming /dev/zero, and a
  // .vtu.series that is itself a FIFO.
  write_text(dir / "a.vtm.series",
             R"({"file-series-version": "1.0", "files": [{"name": "pipe.vtm", "time": 0}]})");
  write_text(dir / "b.vtu.series", R"({"file-series-version": "1.0", "files": [)"
                                   R"({"name": "ok.vtu", "time": 0}, {"name": "/dev/zero", "time": 1}]})");
  fifo(dir, "c.vtu.series");
  for (const char* list : {"a.vtm.series", "b.vtu.series", "c.vtu.series"}) {
    auto r = run("build " + quote(dir / list) + " -o " + quote(dir / "o.tsp"));
    EXPECT_EQ(r.exit_code, 1) << list << ": " << r.err;
    EXPECT_TRUE(has(r.err, list) && has(r.err, "is not a regular file")) << r.err;
  }
}

TEST(HostileInputCli, FifoOrDeviceAsAPlayerScriptIsRefusedBeforeAnyWindow) {
  const fs::path dir = tsptest::temp_dir(), tsp = dir / "s.tsp";
  ASSERT_EQ(run("generate shock -o " + quote(dir / "s.h5") + " --dims 8 --steps 2").exit_code, 0);
  ASSERT_EQ(run("build " + quote(dir / "s.h5") + " -o " + quote(tsp)).exit_code, 0);
  for (const fs::path script : {fifo(dir, "pipe.script"), fs::path("/dev/zero")}) {
    auto r = run("play " + quote(tsp) + " --script " + quote(script));
    EXPECT_EQ(r.exit_code, 1) << script << ": " << r.err;
    EXPECT_TRUE(has(r.err, script.string() + ": player script is not a regular file")) << r.err;
  }
}

TEST(HostileInputCli, FifoOrDeviceAsADiffInputIsRefusedAtOnce) {
  const fs::path dir = tsptest::temp_dir();
  for (const fs::path png : {fifo(dir, "pipe.png"), fs::path("/dev/zero")}) {
    auto r = run("diff " + quote(png) + " " + quote(png));
    EXPECT_EQ(r.exit_code, 1) << png << ": " << r.err;
    EXPECT_TRUE(has(r.err, png.string() + ": PNG image is not a regular file")) << r.err;
  }
}

// A FIFO named like an HDF5 file: the probe for a VTKHDF mesh opened it (H5Fis_hdf5) and waited
// for a writer forever.
TEST(HostileInputCli, AFifoNamedLikeAnHdfFileIsRefusedAtOnce) {
  const fs::path dir = tsptest::temp_dir(), pipe = fifo(dir, "pipe.h5");
  for (const std::string args : {"build " + quote(pipe) + " -o " + quote(dir / "o.tsp"),
                                  "play " + quote(pipe) + " --cache-dir " + quote(dir / "c")}) {
    auto r = run(args);
    EXPECT_EQ(r.exit_code, 1) << args << ": " << r.err;
    EXPECT_TRUE(has(r.err, pipe.string() + ": input is not a regular file")) << r.err;
  }
}

TEST(HostileInputCli, HdfExternalStorageIsRefusedUnlessAllowedAndMustBeARegularFile) {
  const fs::path dir = tsptest::temp_dir();
  // A regular external file holding the samples: refused without --allow-external, built with
  // it (the .tsp then holds exactly those values).
  const std::vector<float> v = sample_values();
  std::ofstream(dir / "raw.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(float)));
  write_external_storage_h5(dir / "ext.h5", (dir / "raw.bin").string());
  auto r = run("build " + quote(dir / "ext.h5") + " -o " + quote(dir / "o.tsp"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(has(r.err, "ext.h5, dataset /f: raw data stored in the external file") &&
              has(r.err, "raw.bin") && has(r.err, "--allow-external"))
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "o.tsp"));
  r = run("build " + quote(dir / "ext.h5") + " --allow-external -o " + quote(dir / "o.tsp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run("info " + quote(dir / "o.tsp") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json info = nlohmann::json::parse(r.out);
  EXPECT_EQ(info["value_range"][0].get<double>(), 0.0);    // sample 0 of step 0
  EXPECT_EQ(info["value_range"][1].get<double>(), 163.0);  // sample 63 of step 1
  // /etc/passwd as external storage: refused without the option.
  write_external_storage_h5(dir / "passwd.h5", "/etc/passwd");
  r = run("build " + quote(dir / "passwd.h5") + " -o " + quote(dir / "p.tsp"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(has(r.err, "/etc/passwd")) << r.err;
  EXPECT_FALSE(fs::exists(dir / "p.tsp"));
  // A FIFO or a device: refused at once even when external storage is allowed.
  for (const fs::path target : {fifo(dir, "pipe.bin"), fs::path("/dev/zero")}) {
    write_external_storage_h5(dir / "dev.h5", target.string());
    r = run("build " + quote(dir / "dev.h5") + " --allow-external -o " + quote(dir / "d.tsp"));
    EXPECT_EQ(r.exit_code, 1) << target << ": " << r.err;
    EXPECT_TRUE(has(r.err, "dev.h5, dataset /f (external storage)") &&
                has(r.err, "is not a regular file"))
        << r.err;
  }
  // play builds raw inputs too: the same refusal.
  r = run("play " + quote(dir / "passwd.h5") + " --cache-dir " + quote(dir / "cache"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(has(r.err, "--allow-external")) << r.err;
}

TEST(HostileInputCli, HdfExternalLinkIsRefusedUnlessAllowed) {
  const fs::path dir = tsptest::temp_dir();
  write_external_link_h5(dir / "link.h5", dir / "target.h5");
  auto r = run("build " + quote(dir / "link.h5") + " -o " + quote(dir / "o.tsp"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(has(r.err, "link.h5: /f is an external link to") && has(r.err, "target.h5"))
      << r.err;
  r = run("build " + quote(dir / "link.h5") + " --allow-external -o " + quote(dir / "o.tsp"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(HostileInputCli, ManyCopiesOfADomainCoveringCellAreRefusedInEitherVoxelizer) {
  const fs::path dir = tsptest::temp_dir(), vtu = dir / "copies.vtu";
  write_hex_copies(vtu, 50000);
  for (const std::string voxelizer : {"locate", "scan"}) {
    auto r = run("build " + quote(vtu) + " --resolution 128 --voxelizer " + voxelizer + " -o " +
                 quote(dir / "o.tsp"));
    EXPECT_EQ(r.exit_code, 1) << voxelizer << ": " << r.err;
    EXPECT_TRUE(has(r.err, "copies.vtu") && has(r.err, "bounding boxes cover more than"))
        << r.err;
  }
  // One copy builds.
  write_hex_copies(dir / "one.vtu", 1);
  EXPECT_EQ(run("build " + quote(dir / "one.vtu") + " --resolution 128 -o " +
                quote(dir / "one.tsp")).exit_code,
            0);
}

TEST(HostileInputCli, AFlatMeshIsAnErrorNotAnEmptyVolume) {
  const fs::path dir = tsptest::temp_dir();
  write_hex_copies(dir / "flat.vtu", 1, true);
  auto r = run("build " + quote(dir / "flat.vtu") + " -o " + quote(dir / "o.tsp"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(has(r.err, "flat.vtu") && has(r.err, "the mesh is flat (every point has z = "))
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "o.tsp"));
}

// A .tsp whose `fields` attribute lists 150,000 names, the last twice: refused, and the check
// is n log n (it took 42 s quadratically).
TEST(HostileInputCli, AHugeFieldListIsCheckedForDuplicatesInBoundedTime) {
  const fs::path dir = tsptest::temp_dir(), tsp = dir / "f.tsp";
  ASSERT_EQ(run("generate shock -o " + quote(dir / "s.h5") + " --dims 8 --steps 2").exit_code, 0);
  ASSERT_EQ(run("build " + quote(dir / "s.h5") + " -o " + quote(tsp)).exit_code, 0);
  std::string names = "f";
  for (int i = 1; i < 150000; ++i) names += "\nfield" + std::to_string(i);
  names += "\nfield7";
  hid_t f = H5Fopen(tsp.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  if (H5Aexists(f, "fields") > 0) H5Adelete(f, "fields");
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, names.size());
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(f, "fields", type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, type, names.data());
  H5Aclose(a);
  H5Sclose(space);
  H5Tclose(type);
  H5Fclose(f);
  auto r = run("info " + quote(tsp));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(has(r.err, "the field 'field7' is listed twice")) << r.err.substr(0, 500);
}

// Issue 48: --field with 1000 names opened and walked the input once per name (400 names: 17 s;
// then a cap of 64 names). The file is now opened once and every name looked up before any
// field is read: the missing ones are named (tests/tsp/voxelize/open_fields_test.cpp counts the
// opens and builds 1000 fields).
TEST(HostileInputCli, AThousandFieldNamesMostlyAbsentAreNamedAtOnce) {
  const fs::path dir = tsptest::temp_dir();
  ASSERT_EQ(run("generate shock -o " + quote(dir / "s.h5") + " --dims 8 --steps 2").exit_code, 0);
  std::string names = "shock";
  for (int i = 1; i < 1000; ++i) names += ",f" + std::to_string(i);
  auto r = run("build " + quote(dir / "s.h5") + " --field " + names + " -o " + quote(dir / "f.tsp"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(has(r.err, "s.h5: 999 of the 1000 fields named not found: 'f1', 'f2',")) << r.err;
  EXPECT_TRUE(has(r.err, "'f20' and 979 more; available 3-D/4-D fields: /shock (2x8x8x8)"))
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "f.tsp"));
}

// A PNG header declaring 16384 x 16384 (1 GiB of RGBA) is refused before anything is decoded.
TEST(HostileInputCli, APngDeclaringAHugeImageIsRefusedBeforeDecoding) {
  const fs::path png = tsptest::test_data_dir() / "../../fuzz/corpus/png/huge_header.png";
  ASSERT_TRUE(fs::exists(png));
  auto r = run("diff " + quote(png) + " " + quote(png));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(has(r.err, "PNG of 16384x16384 pixels, expected at most 67108864 pixels")) << r.err;
}

TEST(HostileInputCli, GeneratedGridsTooLargeForMemoryAreUsageErrors) {
  auto r = run("generate shock -o " + quote(tsptest::temp_dir() / "g.h5") +
               " --dims 2048,2048,2048");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(has(r.err, "8589934592 samples per step, more than the 1073741824")) << r.err;
  r = run("generate shock -o " + quote(tsptest::temp_dir() / "g.h5") +
          " --dims 1024,1024,1024 --steps 4096");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(has(r.err, "more than the 68719476736")) << r.err;
}

TEST(HostileInputCli, SpacingsThatCannotBeDrawnAreRefusedNamingTheAxis) {
  // A denormal step, or two normal steps 1e600 apart: accepted, every frame would be blank.
  const fs::path dir = tsptest::temp_dir();
  ASSERT_EQ(run("generate shock -o " + quote(dir / "s.h5") + " --dims 8 --steps 1").exit_code, 0);
  for (const auto& [spacing, why] :
       {std::pair<std::string, std::string>{"5e-324,1,1", "x spacing 4.94066e-324 is not a positive normal"},
        {"1e300,1e-300,1", "differ by a factor"},
        {"1,inf,1", "three finite numbers"}}) {
    auto r = run("build " + quote(dir / "s.h5") + " --spacing " + spacing + " -o " +
                 quote(dir / "s.tsp"));
    EXPECT_EQ(r.exit_code, 2) << spacing << ": " << r.err;
    EXPECT_TRUE(has(r.err, "--spacing")) << r.err;
    EXPECT_TRUE(has(r.err, why)) << r.err;
    EXPECT_FALSE(fs::exists(dir / "s.tsp"));
  }
}

TEST(HostileInputCli, ATransferFunctionRangeOfInfiniteWidthIsRefused) {
  const fs::path dir = tsptest::temp_dir(), tsp = dir / "s.tsp", tf = dir / "wide.json";
  ASSERT_EQ(run("generate shock -o " + quote(dir / "s.h5") + " --dims 8 --steps 2").exit_code, 0);
  ASSERT_EQ(run("build " + quote(dir / "s.h5") + " -o " + quote(tsp)).exit_code, 0);
  auto r = run("render " + quote(tsp) + " --tf-range -1e308:1e308 --size 16x16 -o " +
               quote(dir / "a"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(has(r.err, "a range of finite width")) << r.err;
  write_text(tf, R"({"range": [-1e308, 1e308], "points": [[-1e308, 1, 0, 0, 1], [1e308, 0, 0, 1, 1]]})");
  r = run("render " + quote(tsp) + " --tf " + quote(tf) + " --size 16x16 -o " + quote(dir / "b"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(has(r.err, "wide.json") && has(r.err, "expected a finite width")) << r.err;
}

// A NetCDF-style scale_factor that is NaN would make every sample NaN: an error, not a warning.
TEST(HostileInputCli, ANanScaleFactorIsAnError) {
  const fs::path dir = tsptest::temp_dir(), h5 = dir / "s.h5";
  ASSERT_EQ(run("generate shock -o " + quote(h5) + " --dims 8 --steps 2").exit_code, 0);
  hid_t f = H5Fopen(h5.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  hid_t ds = H5Dopen2(f, "shock", H5P_DEFAULT);
  ASSERT_GE(ds, 0);
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(ds, "scale_factor", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  H5Awrite(a, H5T_NATIVE_DOUBLE, &nan);
  H5Aclose(a);
  H5Sclose(space);
  H5Dclose(ds);
  H5Fclose(f);
  auto r = run("build " + quote(h5) + " -o " + quote(dir / "o.tsp"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(has(r.err, "attribute scale_factor is nan, expected a finite number")) << r.err;
  EXPECT_FALSE(fs::exists(dir / "o.tsp"));
}

// VTKHDF meshes: Version 99 refused as for image data; step times that repeat or decrease
// refused as .pvd and .series lists refuse them.
TEST(HostileInputCli, VtkhdfMeshVersionAndTimesAreChecked) {
  const fs::path dir = tsptest::temp_dir();
  fs::copy_file(tsptest::test_data_dir() / "vtu" / "mesh_0.hdf", dir / "v99.hdf");
  hid_t f = H5Fopen((dir / "v99.hdf").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  hid_t g = H5Gopen2(f, "/VTKHDF", H5P_DEFAULT);
  if (H5Aexists(g, "Version") > 0) H5Adelete(g, "Version");
  const hsize_t two = 2;
  hid_t space = H5Screate_simple(1, &two, nullptr);
  hid_t a = H5Acreate2(g, "Version", H5T_NATIVE_INT, space, H5P_DEFAULT, H5P_DEFAULT);
  const int version[2] = {99, 0};
  H5Awrite(a, H5T_NATIVE_INT, version);
  H5Aclose(a);
  H5Sclose(space);
  H5Gclose(g);
  H5Fclose(f);
  auto r = run("build " + quote(dir / "v99.hdf") + " -o " + quote(dir / "o.tsp"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(has(r.err, "v99.hdf, /VTKHDF: VTKHDF major version 99, expected 1 or 2")) << r.err;

  fs::copy_file(tsptest::test_data_dir() / "vtu" / "transient.hdf", dir / "times.hdf");
  f = H5Fopen((dir / "times.hdf").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  hid_t ds = H5Dopen2(f, "/VTKHDF/Steps/Values", H5P_DEFAULT);
  ASSERT_GE(ds, 0);
  hid_t s = H5Dget_space(ds);
  std::vector<double> times(std::size_t(H5Sget_simple_extent_npoints(s)), 1.0);  // all alike
  ASSERT_GE(times.size(), 2u);
  H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, times.data());
  H5Sclose(s);
  H5Dclose(ds);
  H5Fclose(f);
  r = run("build " + quote(dir / "times.hdf") + " --field f -o " + quote(dir / "o.tsp"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(has(r.err, "times.hdf, /VTKHDF/Steps/Values: time of step 1") &&
              has(r.err, "times must increase"))
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "o.tsp"));
}

}  // namespace
