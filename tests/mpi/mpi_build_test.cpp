// tspplay-mpi build (src/mpi, tsp/build's BuildPartition): the file N ranks write holds exactly
// the serial build's bricks, stencil, statistics and metadata, whatever N; a failing build
// leaves no output. Runs when MPI was found at configure time (scripts/install-deps.sh --mpi).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/mpi_run.h"
#include "support/paths.h"
#include "support/tsp_compare.h"

namespace {

namespace fs = std::filesystem;
using tsptest::quote;

using tsptest::have_mpi;
using tsptest::run_mpi;

TEST(MpiBuild, RanksWriteTheSerialFile) {
  TSPTEST_REQUIRE(have_mpi(), "MPI not found at configure time (install-deps.sh --mpi)");
  const fs::path dir = tsptest::temp_dir();
  const fs::path in = dir / "two.h5", vortex = dir / "vortex.h5", serial = dir / "serial.tsp";
  // Uneven dims: partial bricks at the far faces; 5 steps: an uneven time tree. Two fields in
  // one file: a tree each.
  const std::string grid = " --dims 40,36,28 --steps 5 -o ";
  ASSERT_EQ(tsptest::run_tspplay("generate shock" + grid + quote(in)).exit_code, 0);
  ASSERT_EQ(tsptest::run_tspplay("generate vortex" + grid + quote(vortex)).exit_code, 0);
  ASSERT_EQ(tsptest::run_command("h5copy -i " + quote(vortex) + " -o " + quote(in) +
                                 " -s /vortex -d /vortex").exit_code, 0);
  const std::string args = " --field shock,vortex --brick 8 -o ";
  const auto s = tsptest::run_tspplay("build " + quote(in) + args + quote(serial));
  ASSERT_EQ(s.exit_code, 0) << s.err;
  for (int ranks : {1, 2, 3}) {
    const fs::path out = dir / ("mpi" + std::to_string(ranks) + ".tsp");
    const auto r = run_mpi(ranks, "build " + quote(in) + args + quote(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("wrote"), std::string::npos) << r.out;  // rank 0's summary, once
    EXPECT_EQ(r.out.find("wrote"), r.out.rfind("wrote")) << r.out;
    tsptest::expect_same_build(serial, out, ranks, "shock");
    if (ranks > 1) {
      const auto info = tsptest::run_tspplay("info " + quote(out));
      EXPECT_NE(info.out.find("built by " + std::to_string(ranks) + " MPI ranks"),
                std::string::npos) << info.out;
    }
    tsptest::expect_same_build(serial, out, ranks, "vortex");
  }
}

TEST(MpiBuild, MeshWithStencil) {
  TSPTEST_REQUIRE(have_mpi(), "MPI not found at configure time (install-deps.sh --mpi)");
  const fs::path dir = tsptest::temp_dir();
  const fs::path in = tsptest::datasets_dir() / "samples/damBreakWithObstacle/"
                                                "damBreakWithObstacle.vtu.series";
  const fs::path serial = dir / "serial.tsp", out = dir / "mpi3.tsp";
  const std::string args = " --field alpha.water --resolution 24 --brick 8 -o ";
  const auto s = tsptest::run_tspplay("build " + quote(in) + args + quote(serial));
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const auto r = run_mpi(3, "build " + quote(in) + args + quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  tsptest::expect_same_build(serial, out, 3);
}

TEST(MpiBuild, FailureNamesTheRankAndLeavesNoOutput) {
  TSPTEST_REQUIRE(have_mpi(), "MPI not found at configure time (install-deps.sh --mpi)");
  const fs::path dir = tsptest::temp_dir();
  const fs::path out = dir / "out.tsp";
  const auto r = run_mpi(2, "build " + quote(dir / "missing.h5") + " -o " + quote(out));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("tspplay-mpi: rank "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("missing.h5"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(dir))  // no temporary left either
    EXPECT_EQ(e.path().filename().string().find(".out.tsp.tmp"), std::string::npos) << e.path();
}

// Rank 1 reads step 1, which is corrupt: it fails mid-build while rank 0 goes on. The job ends
// with rank 1's error, no output appears, and the next build of the same output removes the
// hidden temporary the killed rank 0 left.
TEST(MpiBuild, RankFailingMidBuildLeavesNoOutput) {
  TSPTEST_REQUIRE(have_mpi(), "MPI not found at configure time (install-deps.sh --mpi)");
  const fs::path dir = tsptest::temp_dir();
  for (const char* f : {"ascii.pvd", "ascii_0.vti", "ascii_1.vti", "ascii_2.vti"})
    fs::copy_file(tsptest::test_data_dir() / "vti" / f, dir / f);
  std::string bad = tsptest::read_file(dir / "ascii_1.vti");
  const std::size_t at = bad.find("1000 1001");
  ASSERT_NE(at, std::string::npos);
  bad.replace(at, 9, "1000 oops");
  {
    std::ofstream(dir / "ascii_1.vti", std::ios::binary) << bad;
  }
  const fs::path out = dir / "out.tsp";
  const std::string args = "build " + quote(dir / "ascii.pvd") + " --field f -o " + quote(out);
  const auto r = run_mpi(2, args);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("tspplay-mpi: rank 1 of 2: error: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("ascii_1.vti, array f: ascii value \"oops\""), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  fs::copy_file(tsptest::test_data_dir() / "vti/ascii_1.vti", dir / "ascii_1.vti",
                fs::copy_options::overwrite_existing);
  const auto again = run_mpi(2, args);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_TRUE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".out.tsp.tmp"), std::string::npos) << e.path();
}

}  // namespace
