// Issue 48, budgets in proportion to the file: small curvilinear and tetrahedral inputs whose
// cost ran far out of proportion (a zlib .vts decoded into gigabytes, stretched hexahedra
// running Newton's method at every voxel, --antialias multiplying the work outside the visit
// budget), and a non-finite coordinate in a later step named as a voxel size. Each ends with
// exit 1 and a message naming the file; the fixtures are made here. Commands run under
// `timeout` (and a memory limit where the old cost was memory), so a regression fails the test
// instead of blocking the suite or the machine; no test asserts a duration.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "support/paths.h"

namespace {

namespace fs = std::filesystem;
using tsptest::quote;

// Far longer than any of these commands takes now, far shorter than the old costs.
const std::string kGuard = "timeout 120 ";
// The old .vts reader took 7.5 GB for the bomb below; a limit well above the 2 GB target stops
// a regression with an allocation failure instead of taking the machine's memory.
const std::string kMemoryGuard = "ulimit -v 4194304; ";

tsptest::RunResult run(const std::string& args) {
  return tsptest::run_command(kMemoryGuard + kGuard + quote(tsptest::tspplay_bin()) + " " + args);
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// VTK's zlib layout of `bytes` zero bytes in blocks of kBlock (UInt32 header: block count, block
// size, last block's size, each block's compressed size, then the blocks). Every block is the
// same compressed run of zeros, so the array inflates about 600:1 (deflate's limit is 1032:1).
std::string zlib_zeros(std::uint64_t bytes) {
  constexpr std::uint32_t kBlock = 32768;
  const auto deflate_zeros = [](std::uint32_t n) {
    std::vector<unsigned char> in(n, 0), out(compressBound(n));
    uLongf len = uLongf(out.size());
    EXPECT_EQ(compress2(out.data(), &len, in.data(), n, 9), Z_OK);
    return std::string(reinterpret_cast<const char*>(out.data()), len);
  };
  const std::uint32_t blocks = std::uint32_t((bytes + kBlock - 1) / kBlock);
  const std::uint32_t last = std::uint32_t(bytes - std::uint64_t(blocks - 1) * kBlock);
  const std::string full = deflate_zeros(kBlock), tail = deflate_zeros(last);
  std::vector<std::uint32_t> header = {blocks, kBlock, last};
  for (std::uint32_t b = 0; b < blocks; ++b)
    header.push_back(std::uint32_t(b + 1 == blocks ? tail.size() : full.size()));
  std::string out(reinterpret_cast<const char*>(header.data()), header.size() * 4);
  for (std::uint32_t b = 0; b + 1 < blocks; ++b) out += full;
  return out + tail;
}

// A .vts declaring n × n × n points whose Points and PointData f are zlib runs of zeros.
void write_vts_bomb(const fs::path& path, int n) {
  const std::uint64_t points = std::uint64_t(n) * n * n;
  const std::string f = zlib_zeros(points * 4), xyz = zlib_zeros(points * 12);
  const std::string extent = "0 " + std::to_string(n - 1);
  std::ofstream(path, std::ios::binary)
      << "<VTKFile type=\"StructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt32\" compressor=\"vtkZLibDataCompressor\"><StructuredGrid "
         "WholeExtent=\"" << extent << " " << extent << " " << extent << "\"><Piece Extent=\""
      << extent << " " << extent << " " << extent
      << "\"><PointData><DataArray type=\"Float32\" Name=\"f\" format=\"appended\" offset=\"0\"/>"
         "</PointData><Points><DataArray type=\"Float32\" Name=\"Points\" "
         "NumberOfComponents=\"3\" format=\"appended\" offset=\""
      << f.size() << "\"/></Points></Piece></StructuredGrid><AppendedData encoding=\"raw\">_"
      << f << xyz << "</AppendedData></VTKFile>";
}

// An ascii .vts of n × n × n points on the unit cube's lattice, f = x + y + z, with `patch`
// applied to the coordinates (x, y, z of point p, i fastest) before writing.
template <typename Patch>
void write_vts(const fs::path& path, int n, Patch patch) {
  std::vector<double> xyz;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int v : {i, j, k}) xyz.push_back(double(v) / (n - 1));
  patch(xyz);
  const std::string extent = "0 " + std::to_string(n - 1);
  std::ofstream out(path);
  out << "<VTKFile type=\"StructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">"
         "<StructuredGrid WholeExtent=\"" << extent << " " << extent << " " << extent
      << "\"><Piece Extent=\"" << extent << " " << extent << " " << extent
      << "\"><PointData><DataArray type=\"Float32\" Name=\"f\" format=\"ascii\">";
  for (std::size_t p = 0; p < xyz.size(); p += 3) out << xyz[p] + xyz[p + 1] + xyz[p + 2] << " ";
  out << "</DataArray></PointData><Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" "
         "format=\"ascii\">";
  for (double v : xyz) out << v << " ";
  out << "</DataArray></Points></Piece></StructuredGrid></VTKFile>";
}

void write_series(const fs::path& path, const std::vector<std::string>& names) {
  std::ofstream out(path);
  out << "{\"file-series-version\": \"1.0\", \"files\": [";
  for (std::size_t i = 0; i < names.size(); ++i)
    out << (i ? ", " : "") << "{\"name\": \"" << names[i] << "\", \"time\": " << i << "}";
  out << "]}";
}

// A 432 KB-class file declaring 300³ points: its zlib blocks inflate ~600:1, within deflate's
// limit, but every point becomes a hexahedron of ~100 bytes (7.5 GB). Refused from the header,
// before anything is decoded or allocated, naming the file, the array and the sizes.
TEST(HostileBudgetCli, AZlibVtsDeclaringHugeGridIsRefusedBeforeDecoding) {
  const fs::path dir = tsptest::temp_dir(), vts = dir / "bomb.vts";
  write_vts_bomb(vts, 300);
  const auto size = fs::file_size(vts);
  ASSERT_LT(size, 1u << 20);
  auto r = run("build " + quote(vts) + " -o " + quote(dir / "o.tsp"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(has(r.err, "bomb.vts, array Points: expected 324000000 bytes of data, found ") &&
              has(r.err, "more than the 64:1 accepted here"))
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "o.tsp"));
  EXPECT_EQ(fs::file_size(vts), size);
}

// 12³ points on the unit cube with its 8 corners moved out to ±1e7 (x mirrored, so the corner
// cells twist): the corner hexahedra's boxes cover the whole grid and Newton's method ran long
// at each of their voxels, finding none (23–30 s). Those iterations count against the visit
// budget now.
TEST(HostileBudgetCli, StretchedHexahedraAreRefusedByTheWeightedVisitBudget) {
  const fs::path dir = tsptest::temp_dir(), vts = dir / "stretched.vts";
  constexpr int kN = 12;
  constexpr double kFar = 1e7;
  write_vts(vts, kN, [](std::vector<double>& xyz) {
    for (int k : {0, kN - 1})
      for (int j : {0, kN - 1})
        for (int i : {0, kN - 1}) {
          const std::size_t p = 3 * std::size_t(i + kN * (j + kN * k));
          const int c[3] = {i, j, k};
          for (int a = 0; a < 3; ++a)
            xyz[p + std::size_t(a)] = (c[a] != 0) == (a == 0) ? -kFar : kFar;
        }
  });
  auto r = run("build " + quote(vts) + " -o " + quote(dir / "o.tsp"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(has(r.err, "stretched.vts") && has(r.err, "Newton iteration counting") &&
              has(r.err, "--hex tetrahedra"))
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "o.tsp"));
  // The same grid unstretched builds.
  write_vts(dir / "plain.vts", kN, [](std::vector<double>&) {});
  r = run("build " + quote(dir / "plain.vts") + " -o " + quote(dir / "plain.tsp"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

// A lattice of 30³ hexahedra (162,000 tetrahedra) tiling a small cube, voxelized at 96³ with
// the two-buffer voxelizer's 5³ = 125 passes: within the visit budget once, far beyond it 125
// times. Refused before sampling, the message naming the factor; --antialias 1 builds.
TEST(HostileBudgetCli, AntialiasPassesCountAgainstTheVisitBudget) {
  const fs::path dir = tsptest::temp_dir(), vts = dir / "cube.vts";
  write_vts(vts, 31, [](std::vector<double>& xyz) {
    for (double& v : xyz) v *= 1e-3;
  });
  const std::string common = "build " + quote(vts) + " --voxelizer two-buffer --resolution 96";
  auto r = run(common + " --antialias 5 -o " + quote(dir / "o.tsp"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(has(r.err, "cube.vts") && has(r.err, "counted 125 times for --antialias 5"))
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "o.tsp"));
  r = run(common + " --antialias 1 -o " + quote(dir / "one.tsp"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

// A series whose second step has a point at -inf (or NaN): named by file and point like any
// bad point, never "voxel size inf" as a usage error.
TEST(HostileBudgetCli, NonFiniteCoordinatesInALaterStepAreNamedByFileAndPoint) {
  const fs::path dir = tsptest::temp_dir();
  write_vts(dir / "g_0.vts", 3, [](std::vector<double>&) {});
  write_series(dir / "g.vts.series", {"g_0.vts", "g_1.vts"});
  for (const double bad : {-std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::quiet_NaN()}) {
    // Point 13, the centre, gets a non-finite x.
    write_vts(dir / "g_1.vts", 3, [&](std::vector<double>& xyz) { xyz[3 * 13] = bad; });
    const std::string shown = std::isnan(bad) ? "nan" : "-inf";
    auto r = run("build " + quote(dir / "g.vts.series") + " -o " + quote(dir / "o.tsp"));
    EXPECT_EQ(r.exit_code, 1) << shown << ": " << r.err;
    EXPECT_TRUE(
        has(r.err, "g_1.vts, piece 0: point 13 has a non-finite coordinate (x = " + shown + ")"))
        << shown << ": " << r.err;
    EXPECT_FALSE(has(r.err, "voxel size")) << r.err;
    EXPECT_FALSE(fs::exists(dir / "o.tsp"));
  }
}

}  // namespace
