// tspplay play on what users open: raw series and several fields, a mesh through the adaptive
// octree, WRF fields on their own grids, File > Open switching files (building raw inputs first)
// and never aborting on a bad one; the docked panels. (Helpers: support/player_run.h.)
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/stat.h>

#include "jobs/playback_tuner.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "gl/context.h"
#include "support/paths.h"
#include "tsp/store/tsp_file.h"
#include "tsp/core/error.h"
#include "tsp/report/image.h"
#include "tsp/report/image_diff.h"
#include "tsp/source/open_source.h"

#include "support/player_run.h"

namespace {

namespace fs = std::filesystem;
using tsptest::run_tspplay;
using namespace tsptest::player;

using tsptest::q;

// play takes build's input options (issue 30 item 1): a raw series with its grid size and type
// plays without a separate build, a different grid size is another cached build, and
// --field A,B builds both fields into one file (the first shown, the other in the field menu).
TEST(Player, PlaysARawSeriesAndSeveralFieldsDirectly) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir(), cache = dir / "cache";
  for (int t = 0; t < 3; ++t) {
    std::vector<float> v(8 * 6 * 4);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = float((i + std::size_t(t) * 7) % 23) / 22.f;
    char name[32];
    std::snprintf(name, sizeof name, "u_%04d.raw", t);
    std::ofstream(dir / name, std::ios::binary)
        .write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(float)));
  }
  const std::string raw = q((dir / "u_%04d.raw").string());
  auto r = run_tspplay("play " + raw + " --raw-dims 8,6,4 --raw-type f32 --cache-dir " + q(cache) +
                       " --size " + kSize + " --screenshot " + q(dir / "raw.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("8x6x4 voxels, 3 steps"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir / "raw.png"));
  r = run_tspplay("play " + raw + " --raw-dims 4,6,8 --cache-dir " + q(cache) + " --size " + kSize +
                  " --screenshot " + q(dir / "raw2.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("4x6x8 voxels, 3 steps"), std::string::npos) << r.out;
  int built = 0;
  for (const auto& e : fs::directory_iterator(cache / "builds")) built += e.path().extension() == ".tsp";
  EXPECT_EQ(built, 2) << "the grid size is part of the cached build's key";
  // Without the grid size: the reader's error, exit 1 or 2, nothing played.
  r = run_tspplay("play " + raw + " --cache-dir " + q(cache) + " --size " + kSize);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("raw"), std::string::npos) << r.err;

  const fs::path h5 = tsptest::test_data_dir() / "h5" / "int16.h5";
  // File > Open (script `open`) with build options as play takes them: the raw series' grid;
  // bad options are play's own error, and the file playing stays.
  const std::string raw_path = (dir / "u_%04d.raw").string();
  const fs::path script = write_script(
      "stats " + (dir / "f.json").string() + "\nfield u64\nstats " + (dir / "g.json").string() +
      "\nopen " + raw_path + " --raw-dims 8,6,4 --raw-type f32\nwait-frames 1\nstats " +
      (dir / "h.json").string() + "\nopen " + raw_path + " --raw-dims 8,6\nwait-frames 1\nstats " +
      (dir / "i.json").string() + "\nquit\n");
  r = run_tspplay("play " + q(h5) + " --field plain,u64 --cache-dir " + q(cache) + " --size " +
                  kSize + " --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json f = read_json(dir / "f.json"), g = read_json(dir / "g.json");
  EXPECT_EQ(f["fields"], nlohmann::json({"plain", "u64"}));
  EXPECT_EQ(f["field"], "plain");
  EXPECT_EQ(g["field"], "u64");
  const nlohmann::json h = read_json(dir / "h.json"), i = read_json(dir / "i.json");
  EXPECT_NE(h["file"].get<std::string>().find((cache / "builds").string()), std::string::npos) << h;
  EXPECT_EQ(h["steps_ready"].size(), 3u);  // the raw series' 3 steps
  EXPECT_NE(r.err.find("--raw-dims '8,6'"), std::string::npos) << r.err;
  EXPECT_EQ(i["file"], h["file"]);
}

// play MESH --octree-error E builds Leven's adaptive octree into the cache (a version-3 file,
// the same picture as the file `build --octree-error` writes), apart from the uniform build of
// the same mesh; File > Open takes the option too.
TEST(Player, PlaysAMeshThroughAnAdaptiveOctree) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir(), cache = dir / "cache", built = dir / "built.tsp";
  const std::string mesh =
      q(tsptest::datasets_dir() / "samples/damBreakWithObstacle/damBreakWithObstacle.vtu.series");
  const std::string opts = " --field alpha.water --resolution 32 --octree-error 5%";
  auto r = run_tspplay("play " + mesh + opts + " --cache-dir " + q(cache) + " --size " + kSize +
                       " --screenshot " + q(dir / "a.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("building its adaptive octree into"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("adaptive octree (E = 0.05)"), std::string::npos) << r.out;
  std::vector<fs::path> builds;
  for (const auto& e : fs::directory_iterator(cache / "builds"))
    if (e.path().extension() == ".tsp") builds.push_back(e.path());
  ASSERT_EQ(builds.size(), 1u);
  EXPECT_TRUE(tsp::TspFile::open(builds[0].string())->tree().octree().has_stops());
  ASSERT_EQ(run_tspplay("build " + mesh + opts + " -o " + q(built)).exit_code, 0);
  ASSERT_EQ(run_tspplay("play " + q(built) + " --size " + kSize + " --screenshot " + q(dir / "b.png"))
                .exit_code,
            0);
  EXPECT_LT(tsp::diff_images(tsp::read_png((dir / "a.png").string()),
                             tsp::read_png((dir / "b.png").string())).mean, kSameFrameDeltaE);
  // File > Open: without the option the uniform grid (a build of its own), with it the octree
  // built above, reused.
  const fs::path script = write_script(
      "open " + mesh.substr(1, mesh.size() - 2) + " alpha.water --resolution 32\nwait-frames 1\nstats " +
      (dir / "u.json").string() + "\nopen " + mesh.substr(1, mesh.size() - 2) +
      " alpha.water --resolution 32 --octree-error 5%\nwait-frames 1\nstats " +
      (dir / "o.json").string() + "\nquit\n");
  r = run_tspplay("play " + q(built) + " --cache-dir " + q(cache) + " --size " + kSize +
                  " --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string u = read_json(dir / "u.json")["file"], o = read_json(dir / "o.json")["file"];
  EXPECT_FALSE(tsp::TspFile::open(u)->tree().octree().has_stops()) << u;
  EXPECT_EQ(o, builds[0].string());
}

// WRF's T, W (15 staggered levels) and QVAPOR played straight from the NetCDF file: built into
// one file, each on its own grid, switching keeps the view (issue 30).
TEST(Player, PlaysSeveralWrfFieldsOnTheirOwnGrids) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path wrf = tsptest::shared_data_dir() / "wrf-katrina" / "ci_test_file.nc";
  if (!fs::exists(wrf)) GTEST_SKIP() << "shared data absent: " << wrf;
  const fs::path dir = tsptest::temp_dir();
  const fs::path script = write_script(
      "stats " + (dir / "t.json").string() + "\nfield W\nstats " + (dir / "w.json").string() +
      "\ntf-range histogram\nstats " + (dir / "h.json").string() + "\ntf-range -1:2\nstats " +
      (dir / "e.json").string() + "\nstep 3\ntf-range step\nstats " + (dir / "s.json").string() +
      "\ntf-range visible\nstats " + (dir / "v.json").string() + "\nquit\n");
  auto r = run_tspplay("play " + q(wrf) + " --field T,W,QVAPOR --cache-dir " + q(dir / "cache") +
                       " --size " + kSize + " --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json t = read_json(dir / "t.json"), w = read_json(dir / "w.json");
  EXPECT_EQ(t["fields"], nlohmann::json({"T", "W", "QVAPOR"}));
  // tf-range (the panel's "fit to bulk"): W's map moves inside its data range (W is near 0 but
  // for a few updrafts: the 1st to 99th percentile is far narrower), then to an explicit one.
  const nlohmann::json h = read_json(dir / "h.json"), e = read_json(dir / "e.json");
  const double lo = h["tf_domain"][0], hi = h["tf_domain"][1];
  EXPECT_GT(lo, double(w["tf_domain"][0]));
  EXPECT_LT(hi, double(w["tf_domain"][1]));
  EXPECT_LT(hi - lo, 0.8 * (double(w["tf_domain"][1]) - double(w["tf_domain"][0])));
  EXPECT_EQ(e["tf_domain"], nlohmann::json({-1.0, 2.0}));
  // tf-range step (the panel's "fit to step"): W's values at step 3, read from the NetCDF file
  // (at their heights: those inside the columns).
  tsp::SourceOptions so;
  so.field = "W";
  auto src = tsp::open_source(wrf.string(), so);
  std::vector<float> all(std::size_t(src->dims().count())), v;
  std::vector<std::uint8_t> inside(all.size());
  src->read_step_inside(3, all, inside);
  for (std::size_t i = 0; i < all.size(); ++i)
    if (inside[i]) v.push_back(all[i]);
  const auto [vlo, vhi] = std::minmax_element(v.begin(), v.end());
  const nlohmann::json st = read_json(dir / "s.json");
  const double tol = 1e-5 * (*vhi - *vlo);
  EXPECT_NEAR(double(st["tf_domain"][0]), *vlo, tol);
  EXPECT_NEAR(double(st["tf_domain"][1]), *vhi, tol);
  // tf-range visible ("fit to view"): the whole volume is in view, so the step's range again.
  const nlohmann::json vis = read_json(dir / "v.json");
  EXPECT_NEAR(double(vis["tf_domain"][0]), *vlo, tol);
  EXPECT_NEAR(double(vis["tf_domain"][1]), *vhi, tol);
  EXPECT_EQ(t["field"], "T");
  EXPECT_EQ(w["field"], "W");
  EXPECT_EQ(t["steps_ready"].size(), 4u);
  EXPECT_EQ(t["file"], w["file"]);
}


// A window large enough docks the panels beside the volume: the volume-only screenshot is the
// view's size (stats say where it is) and matches `tspplay render` at that size; hidden panels
// (Tab, or `panels off`) give the volume the whole window.
TEST(Player, DockedPanelsLeaveTheVolumeItsOwnViewAndTabHidesThem) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  fs::path script = write_script("step 1\nwait-frames 2\nstats " + (dir / "d.json").string() +
                                 "\nscreenshot " + (dir / "d.png").string() + "\nscreenshot-ui " +
                                 (dir / "ui.png").string() + "\npanels off\nwait-frames 2\nstats " +
                                 (dir / "f.json").string() + "\nscreenshot " +
                                 (dir / "f.png").string() + "\nquit\n");
  auto r = run_tspplay("play " + q(tsp) + " --size 900x600 --trace --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("trace: panels off"), std::string::npos) << r.out;
  const nlohmann::json d = read_json(dir / "d.json"), f = read_json(dir / "f.json");
  ASSERT_TRUE(d["docked"].get<bool>());
  const int vw = d["view"][2], vh = d["view"][3];
  EXPECT_EQ(vw, 900 - 370);  // the side panel's width
  EXPECT_LT(vh, 600);
  const tsp::Image docked = tsp::read_png((dir / "d.png").string());
  ASSERT_EQ(docked.width, vw);
  ASSERT_EQ(docked.height, vh);
  EXPECT_GT(covered(docked), 0.02);
  fs::path out = dir / "frames";
  const std::string size = std::to_string(vw) + "x" + std::to_string(vh);
  auto rr = run_tspplay("render " + q(tsp) + " --steps 1 --size " + size + " -o " + q(out));
  ASSERT_EQ(rr.exit_code, 0) << rr.err;
  EXPECT_LT(tsp::diff_images(docked, tsp::read_png((out / "step_0001.png").string())).mean,
            kSameFrameDeltaE);
  // The UI screenshot is the whole window; left of the side panel it is the volume.
  const tsp::Image ui = tsp::read_png((dir / "ui.png").string());
  EXPECT_EQ(ui.width, 900);
  EXPECT_FALSE(f["docked"].get<bool>());
  EXPECT_EQ(f["view"][2].get<int>(), 900);
  EXPECT_EQ(tsp::read_png((dir / "f.png").string()).height, 600);
}

// File > Open from a script: another .tsp plays at once; a raw input is built into the cache
// folder first (on a thread; the script waits), then plays; the picture is the new file's.
TEST(Player, OpenSwitchesToAnotherFileAndBuildsARawInputFirst) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir(), other = dir / "v.tsp", h5 = dir / "raw.h5";
  ASSERT_EQ(run_tspplay("generate vortex -o " + q(dir / "v.h5") + " --dims 24,22,20 --steps 3")
                .exit_code, 0);
  ASSERT_EQ(run_tspplay("build " + q(dir / "v.h5") + " -o " + q(other)).exit_code, 0);
  ASSERT_EQ(run_tspplay("generate shock -o " + q(h5) + " --dims 20,18,16 --steps 5").exit_code, 0);
  fs::path tsp = make_tsp();
  fs::path script = write_script(
      "open " + other.string() + "\nwait-frames 2\nstats " + (dir / "a.json").string() +
      "\nscreenshot " + (dir / "a.png").string() + "\nopen " + h5.string() +
      " shock\nwait-frames 2\nstats " + (dir / "b.json").string() + "\nopen " +
      (dir / "missing.h5").string() + "\nwait-frames 1\nstats " + (dir / "c.json").string() +
      "\nquit\n");
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --cache-dir " +
                       q(dir / "cache") + " --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_json(dir / "a.json")["file"], other.string());
  EXPECT_LT(tsp::diff_images(tsp::read_png((dir / "a.png").string()), render_step(other, 0)).mean,
            kSameFrameDeltaE);
  const std::string built = read_json(dir / "b.json")["file"];
  EXPECT_NE(built.find((dir / "cache" / "builds").string()), std::string::npos) << built;
  EXPECT_EQ(read_json(dir / "b.json")["steps_ready"].size(), 5u);  // the raw input's 5 steps
  EXPECT_NE(r.out.find("building it into"), std::string::npos) << r.out;
  // A missing input is reported (stderr and the status line) and the player keeps playing.
  EXPECT_NE(r.err.find("missing.h5"), std::string::npos) << r.err;
  EXPECT_EQ(read_json(dir / "c.json")["file"], built);
}

// File > Open with the reference metric chosen: the new file's metric was made lazily, which the
// reference metric cannot be (tsp::LazyErrors throws), so the open failed after the old renderer
// was dropped and the next frame crashed (SIGSEGV). Now the opened file plays with its reference
// errors, as render draws it.
TEST(Player, OpenWithTheReferenceMetricPlaysTheOpenedFile) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir(), tsp = make_tsp(), other = dir / "v.tsp";
  ASSERT_EQ(run_tspplay("generate vortex -o " + q(dir / "v.h5") + " --dims 24,22,20 --steps 3")
                .exit_code, 0);
  ASSERT_EQ(run_tspplay("build " + q(dir / "v.h5") + " -o " + q(other)).exit_code, 0);
  const fs::path script = write_script(
      "metric reference\nwait-frames 1\nopen " + other.string() + "\nwait-frames 2\nstats " +
      (dir / "a.json").string() + "\nscreenshot " + (dir / "a.png").string() + "\nquit\n");
  const auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --no-session --script " +
                             q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("cannot be evaluated lazily"), std::string::npos) << r.err;
  EXPECT_EQ(read_json(dir / "a.json")["file"], other.string());
  EXPECT_LT(tsp::diff_images(tsp::read_png((dir / "a.png").string()), render_step(other, 0)).mean,
            kSameFrameDeltaE);
}

// File > Open (script `open`) never aborts (issue 28 item 7): a missing path, a device, a FIFO,
// a bad .vtu and an HDF5 file refused for its external storage are each reported on stderr (and
// in the trace) while the old file keeps playing; a valid input that needs building is built
// and played; `open X` right before `quit` still reports X's failure.
TEST(Player, OpenNeverAbortsAndReportsEveryFailure) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir(), tsp = make_tsp(), h5 = dir / "raw.h5";
  ASSERT_EQ(run_tspplay("generate vortex -o " + q(h5) + " --dims 20,18,16 --steps 3").exit_code, 0);
  std::ofstream(dir / "bad.vtu") << "<VTKFile type=\"UnstructuredGrid\"><Unstructured";
  ASSERT_EQ(mkfifo((dir / "pipe.h5").c_str(), 0600), 0);
  // HDF5 files whose only dataset is stored in another file (/etc/passwd; 64 floats of ours):
  // refused without --allow-external.
  auto write_external = [](const fs::path& path, const std::string& external) {
    const hsize_t dims[3] = {4, 4, 4};
    hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    hid_t space = H5Screate_simple(3, dims, nullptr);
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_external(dcpl, external.c_str(), 0, 256);
    H5Dclose(H5Dcreate2(f, "d", H5T_IEEE_F32LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT));
    H5Pclose(dcpl);
    H5Sclose(space);
    H5Fclose(f);
  };
  write_external(dir / "ext.h5", "/etc/passwd");
  {
    std::vector<float> v(64);
    for (int i = 0; i < 64; ++i) v[std::size_t(i)] = float(i);
    std::ofstream(dir / "raw.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(v.data()), 256);
  }
  write_external(dir / "ext_ok.h5", (dir / "raw.bin").string());
  const std::vector<std::string> bad = {(dir / "missing.h5").string(), "/dev/zero",
                                        (dir / "pipe.h5").string(), (dir / "bad.vtu").string(),
                                        (dir / "ext.h5").string()};
  std::string text;
  for (std::size_t i = 0; i < bad.size(); ++i)
    text += "open " + bad[i] + "\nwait-frames 1\nstats " + (dir / ("bad" + std::to_string(i) + ".json")).string() + "\n";
  text += "open " + h5.string() + "\nwait-frames 1\nstats " + (dir / "built.json").string() +
          "\nopen " + (dir / "last.h5").string() + "\nquit\n";
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --trace --cache-dir " +
                       q(dir / "cache") + " --script " + q(write_script(text)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (std::size_t i = 0; i < bad.size(); ++i) {
    EXPECT_NE(r.err.find("open " + bad[i] + ": "), std::string::npos) << bad[i] << "\n" << r.err;
    EXPECT_EQ(r.err.find("open " + bad[i] + ": " + bad[i] + ":"), std::string::npos)
        << "the path once: " << r.err;
    EXPECT_NE(r.out.find("trace: open " + bad[i] + " failed: "), std::string::npos) << r.out;
    EXPECT_EQ(read_json(dir / ("bad" + std::to_string(i) + ".json"))["file"], tsp.string());
  }
  EXPECT_NE(r.err.find("--allow-external"), std::string::npos) << r.err;
  const std::string built = read_json(dir / "built.json")["file"];
  EXPECT_NE(built.find((dir / "cache" / "builds").string()), std::string::npos) << built;
  EXPECT_EQ(read_json(dir / "built.json")["steps_ready"].size(), 3u);  // the input's 3 steps
  EXPECT_NE(r.err.find("open " + (dir / "last.h5").string() + ": "), std::string::npos) << r.err;
  // With --allow-external, File > Open builds such a file.
  r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --allow-external --cache-dir " +
                  q(dir / "cache") + " --script " +
                  q(write_script("open " + (dir / "ext_ok.h5").string() + "\nwait-frames 1\nstats " +
                                 (dir / "ext.json").string() + "\nquit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string ext_built = read_json(dir / "ext.json")["file"];
  EXPECT_NE(ext_built.find("ext_ok.h5-"), std::string::npos) << ext_built << r.err;
}

}  // namespace
