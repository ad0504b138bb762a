// tspplay build / info end to end: the JSON of `info --json --nodes` against the tree shape and
// brute-force statistics of the same input read independently, and exit codes on bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "support/json_file.h"
#include "support/paths.h"
#include "tsp/source/open_source.h"
#include "tsp/source/volume_source.h"
#include "tsp/tree/tsp_tree.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using tsptest::run_tspplay;

using tsptest::katrina_file;
using tsptest::q;

// Every step of the input, read through the library's reader (not through the .tsp file); WRF
// files with their levels as stored (--vertical-levels native: no stencil, every sample counts).
struct Series {
  tsp::Dims dims;
  std::vector<std::vector<float>> steps;
  float at(int x, int y, int z, int t) const {
    return steps[t][x + std::size_t(dims.x) * (y + std::size_t(dims.y) * z)];
  }
};

Series read_all(const std::string& input, const std::string& field) {
  tsp::SourceOptions o;
  o.field = field;
  o.vertical.mode = tsp::VerticalLevels::Mode::native;
  auto src = tsp::open_source(input, o);
  Series s{src->dims(), {}};
  for (int t = 0; t < src->steps(); ++t) {
    s.steps.emplace_back(std::size_t(s.dims.count()));
    src->read_step(t, s.steps.back());
  }
  return s;
}

json info_json(const fs::path& tsp_file, const std::string& extra = " --nodes") {
  auto r = run_tspplay("info " + q(tsp_file) + " --json" + extra);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return json::parse(r.out);
}

// Checks the summary and every node record against the shape and a brute-force computation.
void check_info(const json& j, const Series& s, int brick) {
  const int T = int(s.steps.size());
  const tsp::TspTree shape(s.dims, T, brick);
  const tsp::Octree& o = shape.octree();
  EXPECT_EQ(j["dims"], json({s.dims.x, s.dims.y, s.dims.z}));
  EXPECT_EQ(j["steps"], T);
  EXPECT_EQ(j["brick"], brick);
  EXPECT_EQ(j["leaf_bricks"], o.brick_count());
  EXPECT_EQ(j["octree_nodes"], o.size());
  EXPECT_EQ(j["tsp_nodes"], shape.size());
  // LOD levels: one row per level, the leaves at level 0, every internal node at its level.
  ASSERT_EQ(j["format_version"], 2);
  const json& lod = j["lod_levels"];
  ASSERT_EQ(int(lod.size()), o.max_lod_level() + 1);
  EXPECT_EQ(lod[0]["bricks"], o.brick_count());
  int level_bricks = 0;
  for (std::size_t k = 1; k < lod.size(); ++k) level_bricks += lod[k]["bricks"].get<int>();
  EXPECT_EQ(level_bricks, o.level_brick_count());
  float lo = INFINITY, hi = -INFINITY;
  for (const auto& step : s.steps)
    for (float v : step) lo = std::min(lo, v), hi = std::max(hi, v);
  EXPECT_EQ(j["value_range"], json({double(lo), double(hi)}));
  const double W = double(hi) - double(lo);

  const json& nodes = j["nodes"];
  ASSERT_EQ(int(nodes.size()), shape.size());
  for (int id = 0; id < shape.size(); ++id) {
    const json& n = nodes[id];
    const int oid = shape.octree_of(id);
    const tsp::Box b = o.node(oid).box;
    const tsp::Span sp = shape.time().span(shape.time_of(id));
    SCOPED_TRACE("node " + std::to_string(id));
    ASSERT_EQ(n["id"], id);
    ASSERT_EQ(n["octree_id"], oid);
    ASSERT_EQ(n["level"], o.node(oid).level);
    ASSERT_EQ(n["box"], json({b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]}));
    ASSERT_EQ(n["span"], json({sp.t0, sp.t1}));
    double sum = 0, mn = INFINITY, mx = -INFINITY, cov = 0;
    const double N = double(b.count()) * sp.length();
    for (int t = sp.t0; t <= sp.t1; ++t)
      for (int z = b.lo[2]; z < b.hi[2]; ++z)
        for (int y = b.lo[1]; y < b.hi[1]; ++y)
          for (int x = b.lo[0]; x < b.hi[0]; ++x) {
            sum += s.at(x, y, z, t);
            mn = std::min(mn, double(s.at(x, y, z, t)));
            mx = std::max(mx, double(s.at(x, y, z, t)));
          }
    const double mean = sum / N;
    double ss = 0;
    for (int z = b.lo[2]; z < b.hi[2]; ++z)
      for (int y = b.lo[1]; y < b.hi[1]; ++y)
        for (int x = b.lo[0]; x < b.hi[0]; ++x) {
          double vs = 0, vss = 0;
          for (int t = sp.t0; t <= sp.t1; ++t) vs += s.at(x, y, z, t);
          const double vm = vs / sp.length();
          for (int t = sp.t0; t <= sp.t1; ++t) {
            ss += (s.at(x, y, z, t) - mean) * (s.at(x, y, z, t) - mean);
            vss += (s.at(x, y, z, t) - vm) * (s.at(x, y, z, t) - vm);
          }
          cov += tsp::coefficient_of_variation(std::sqrt(vss / sp.length()), vm, W);
        }
    const double sd = std::sqrt(ss / N);
    ASSERT_NEAR(n["mean"].get<double>(), mean, 1e-9 * std::max(1.0, std::fabs(mean)));
    ASSERT_NEAR(n["std"].get<double>(), sd, 1e-9 * std::max(1.0, sd));
    ASSERT_EQ(n["min"].get<double>(), mn);
    ASSERT_EQ(n["max"].get<double>(), mx);
    const double es = tsp::coefficient_of_variation(sd, mean, W), et = cov / double(b.count());
    ASSERT_NEAR(n["spatial_error"].get<double>(), es, 1e-6 * std::max(1.0, es));
    ASSERT_NEAR(n["temporal_error"].get<double>(), et, 1e-6 * std::max(1.0, et));
  }
}

TEST(BuildInfoCli, GeneratedSeriesMatchesBruteForce) {
  const fs::path dir = tsptest::temp_dir();
  auto g = run_tspplay("generate vortex -o " + q(dir / "v.h5") + " --dims 23,17,9 --steps 5");
  ASSERT_EQ(g.exit_code, 0) << g.err;
  auto r = run_tspplay("build " + q(dir / "v.h5") + " -o " + q(dir / "v.tsp") +
                       " --brick 8 --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // no progress bar and no warning when stderr is not a terminal
  EXPECT_NE(r.out.find("wrote"), std::string::npos) << r.out;
  check_info(info_json(dir / "v.tsp"), read_all((dir / "v.h5").string(), ""), 8);
}

TEST(BuildInfoCli, KatrinaTemperature) {
  if (!fs::exists(katrina_file())) GTEST_SKIP() << "shared data absent: " << katrina_file();
  const fs::path dir = tsptest::temp_dir();
  auto r = run_tspplay("build " + q(katrina_file()) + " --field T --vertical-levels native -o " +
                       q(dir / "t.tsp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = info_json(dir / "t.tsp");
  EXPECT_EQ(j["dims"], json({48, 48, 14}));
  EXPECT_EQ(j["field"], "T");
  // No --brick: the default for 48 × 48 × 14 (a quarter of 48 is 12, nearest power of two 16).
  check_info(j, read_all(katrina_file().string(), "T"), 16);

  auto h = run_tspplay("info " + q(dir / "t.tsp"));
  ASSERT_EQ(h.exit_code, 0) << h.err;
  for (const char* s : {"48x48x14", "steps         4", "ci_test_file.nc", "e_ss mean",
                        "times         2005-08-28 12:00 .. 2005-08-28 21:00"})
    EXPECT_NE(h.out.find(s), std::string::npos) << s << "\n" << h.out;
  // WRF's Times: seconds since the first date, kept in the file.
  EXPECT_EQ(j["time_units"], "seconds since 2005-08-28 12:00:00");
  EXPECT_EQ(j["times"], json({0, 10800, 21600, 32400}));
  // Without --nodes the JSON has no node list.
  EXPECT_FALSE(info_json(dir / "t.tsp", "").contains("nodes"));
}

// A CF time coordinate's units and calendar (tests/data/h5/map_over_time.nc: 0, 6, 12 "hours
// since 2000-01-01 00:00:00") travel into the .tsp file and show as dates in info and in
// render's frames.json.
TEST(BuildInfoCli, CfTimeUnitsShowAsDates) {
  const fs::path dir = tsptest::temp_dir();
  const fs::path nc = tsptest::test_data_dir() / "h5" / "map_over_time.nc";
  auto r = run_tspplay("build " + q(nc) + " --field T -o " + q(dir / "t.tsp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = info_json(dir / "t.tsp", "");
  EXPECT_EQ(j["times"], json({0, 6, 12}));
  EXPECT_EQ(j["time_units"], "hours since 2000-01-01 00:00:00");
  EXPECT_EQ(j["time_calendar"], "standard");
  const auto h = run_tspplay("info " + q(dir / "t.tsp"));
  EXPECT_NE(h.out.find("times         2000-01-01 00:00 .. 2000-01-01 12:00"), std::string::npos)
      << h.out;
  r = run_tspplay("render " + q(dir / "t.tsp") + " --size 32x24 -o " + q(dir / "f"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json frames = tsptest::frames_json(dir / "f")["frames"];
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[1]["time"], 6);
  EXPECT_EQ(frames[1]["time_text"], "2000-01-01 06:00");
}

// WRF's T (mass points, 14 levels) and W (staggered, 15 levels) in one file, as stored: each
// keeps its grid, W half a layer below T, and both render in one frame.
TEST(BuildInfoCli, StaggeredWrfFieldsKeepTheirGrids) {
  if (!fs::exists(katrina_file())) GTEST_SKIP() << "shared data absent: " << katrina_file();
  const fs::path dir = tsptest::temp_dir();
  auto r = run_tspplay("build " + q(katrina_file()) + " --field T,W --vertical-levels native -o " +
                       q(dir / "tw.tsp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json t = info_json(dir / "tw.tsp", " --field T");
  const json w = info_json(dir / "tw.tsp", " --nodes --field W");
  EXPECT_EQ(t["dims"], json({48, 48, 14}));
  EXPECT_EQ(w["dims"], json({48, 48, 15}));
  const double dz = double(w["spacing"][2]);
  EXPECT_DOUBLE_EQ(double(t["spacing"][2]), dz);
  EXPECT_NEAR(double(t["origin"][2]) - double(w["origin"][2]), 0.5 * dz, 1e-6 * dz);
  check_info(w, read_all(katrina_file().string(), "W"), 16);
  for (const char* f : {"T", "W"})
    EXPECT_EQ(run_tspplay("render " + q(dir / "tw.tsp") + " --field " + f + " --size 32x24 -o " +
                          q(dir / f)).exit_code, 0) << f;
}

// WRF's levels at their heights (the default): T's 14 uneven levels resampled from the
// geopotential to 78 planes 72.9 m apart (tests/tsp/source/level_resample_test.cpp checks the
// values), said by info's source line; the voxels beyond a column's levels are outside (the
// stencil). W, on the staggered levels, gets its own grid from the ground up.
TEST(BuildInfoCli, WrfLevelsAtTheirHeights) {
  if (!fs::exists(katrina_file())) GTEST_SKIP() << "shared data absent: " << katrina_file();
  const fs::path dir = tsptest::temp_dir();
  auto r = run_tspplay("build " + q(katrina_file()) + " --field T,W -o " + q(dir / "tw.tsp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json t = info_json(dir / "tw.tsp", " --field T");
  EXPECT_EQ(t["dims"], json({48, 48, 78}));
  EXPECT_NEAR(double(t["spacing"][2]), 72.863, 1e-3);
  EXPECT_NEAR(double(t["origin"][2]), 29.885, 1e-3);
  EXPECT_EQ(t["stencil"], true);
  const json w = info_json(dir / "tw.tsp", " --field W");
  EXPECT_EQ(w["dims"], json({48, 48, 104}));
  EXPECT_DOUBLE_EQ(double(w["origin"][2]), 0);
  const auto h = run_tspplay("info " + q(dir / "tw.tsp"));
  ASSERT_EQ(h.exit_code, 0) << h.err;
  EXPECT_NE(h.out.find("ci_test_file.nc, dataset /T, levels resampled from 14 uneven levels "
                       "(geopotential) to 78 at 72.9 m"),
            std::string::npos)
      << h.out;
  // A chosen count or spacing.
  r = run_tspplay("build " + q(katrina_file()) + " --field T --vertical-levels 40 -o " +
                  q(dir / "n.tsp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(info_json(dir / "n.tsp", "")["dims"], json({48, 48, 40}));
  r = run_tspplay("build " + q(katrina_file()) + " --field T --vertical-levels 100m -o " +
                  q(dir / "m.tsp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json m = info_json(dir / "m.tsp", "");
  EXPECT_EQ(m["dims"], json({48, 48, 57}));  // round(5610.5 / 100) + 1
  EXPECT_DOUBLE_EQ(double(m["spacing"][2]), 100);
}

// --field A,B: one tree each in one file. info lists the fields and describes any one of them
// with --field, each matching the brute force over its own dataset; render and metrics take
// --field too.
TEST(BuildInfoCli, SeveralFieldsInOneFile) {
  const fs::path dir = tsptest::temp_dir(), h5 = tsptest::test_data_dir() / "h5" / "int16.h5";
  auto r = run_tspplay("build " + q(h5) + " --field plain,u64 --brick 8 -o " + q(dir / "m.tsp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json first = info_json(dir / "m.tsp");
  EXPECT_EQ(first["fields"], json({"plain", "u64"}));
  EXPECT_EQ(first["field"], "plain");
  check_info(first, read_all(h5.string(), "plain"), 8);
  const json second = info_json(dir / "m.tsp", " --nodes --field u64");
  EXPECT_EQ(second["field"], "u64");
  check_info(second, read_all(h5.string(), "u64"), 8);
  const auto text = run_tspplay("info " + q(dir / "m.tsp"));
  EXPECT_NE(text.out.find("fields        plain, u64"), std::string::npos) << text.out;
  for (const std::string& cmd : {"render " + q(dir / "m.tsp") + " --field u64 --size 32x24 -o " +
                                    q(dir / "f"),
                                "metrics " + q(dir / "m.tsp") + " --field u64 --tf preset:sparse"})
    EXPECT_EQ(run_tspplay(cmd).exit_code, 0) << cmd;
  const auto bad = run_tspplay("info " + q(dir / "m.tsp") + " --field density");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("holds the field(s) plain, u64"), std::string::npos) << bad.err;
  // A field over other steps (f: 4 steps, single: 1), or one named twice: refused, nothing
  // written.
  const fs::path grid4d = tsptest::test_data_dir() / "h5" / "grid4d.h5";
  EXPECT_EQ(run_tspplay("build " + q(grid4d) + " --field f,single -o " + q(dir / "x.tsp")).exit_code,
            1);
  EXPECT_EQ(run_tspplay("build " + q(h5) + " --field plain,plain -o " + q(dir / "x.tsp")).exit_code,
            2);
  EXPECT_FALSE(fs::exists(dir / "x.tsp"));
}

TEST(BuildInfoCli, RangeOptionSetsTheQuantizationRange) {
  if (!fs::exists(katrina_file())) GTEST_SKIP() << "shared data absent: " << katrina_file();
  const fs::path dir = tsptest::temp_dir();
  auto r = run_tspplay("build " + q(katrina_file()) + " --field T --brick 16 --range=-5:40 -o " +
                       q(dir / "t.tsp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = info_json(dir / "t.tsp", "");
  EXPECT_EQ(j["value_range"], json({-5.0, 40.0}));
  EXPECT_GT(j["data_range"][1].get<double>(), 40.0);  // T reaches about 43: clamped
  EXPECT_EQ(j["brick"], 16);
}

TEST(BuildInfoCli, NonFiniteSamplesAreCountedAndWarned) {
  const fs::path dir = tsptest::temp_dir();
  std::vector<float> v(4 * 3 * 2, 1.5f);
  v[3] = NAN;
  v[7] = INFINITY;
  for (int t = 0; t < 2; ++t) {
    v[0] = float(t);
    std::ofstream(dir / ("s" + std::to_string(t) + ".raw"), std::ios::binary)
        .write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * 4));
  }
  auto r = run_tspplay("build " + q(dir / "s%d.raw") + " --raw-dims 4,3,2 --raw-type f32 -o " +
                       q(dir / "s.tsp"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: 4 NaN/Inf samples replaced"), std::string::npos) << r.err;
  const json j = info_json(dir / "s.tsp", "");
  EXPECT_EQ(j["nonfinite_count"], 4);
  EXPECT_EQ(j["data_range"], json({0.0, 1.5}));
  EXPECT_EQ(j["steps"], 2);
}

TEST(BuildInfoCli, BadInputGivesClearErrorsAndNoOutput) {
  if (!fs::exists(katrina_file())) GTEST_SKIP() << "shared data absent: " << katrina_file();
  const fs::path dir = tsptest::temp_dir();
  const std::string out = " -o " + q(dir / "x.tsp");
  struct Case {
    std::string args;
    int code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"build " + q(dir / "missing.h5") + out, 1, "missing.h5"},
      {"build " + q(katrina_file()) + " --field NOPE" + out, 1, "NOPE"},
      {"build " + q(katrina_file()) + " --field T --brick 12" + out, 2, "brick size 12"},
      {"build " + q(katrina_file()) + " --field T --range 5" + out, 2, "expected LO:HI"},
      {"build " + q(katrina_file()) + " --field T --range 5:1" + out, 2, "expected finite LO < HI"},
      {"build " + q(katrina_file()) + " --field T --range a:1" + out, 2, "not a number"},
      {"build " + q(katrina_file()) + " --field T -o " + q(dir / "no" / "x.tsp"), 1,
       "does not exist"},
      {"build " + q(katrina_file()) + " --field T", 2, "--output is required"},
      {"build " + q(katrina_file()) + " --field T --vertical-levels 1" + out, 2,
       "--vertical-levels '1': expected finest, native, a level count N (2 to 4096) or a spacing "
       "in metres such as 50m"},
      {"build " + q(katrina_file()) + " --field T --vertical-levels fine" + out, 2,
       "--vertical-levels 'fine': expected finest"},
      {"build " + q(katrina_file()) + " --field T --vertical-levels=-5m" + out, 2,
       "--vertical-levels '-5m': expected finest"},
      {"build " + q(katrina_file()) + " --field T --vertical-levels 0.5m" + out, 2,
       "--vertical-levels 0.5m would make 11222 levels over 5610.5 m; at most 4096"},
      {"build " + q(katrina_file()) + " --field T --vertical-levels 9000m" + out, 2,
       "--vertical-levels 9000m: the spacing is larger than the levels' whole range, 5610.5 m"},
  };
  for (const Case& c : cases) {
    auto r = run_tspplay(c.args);
    EXPECT_EQ(r.exit_code, c.code) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
  }
  EXPECT_TRUE(fs::is_empty(dir)) << fs::directory_iterator(dir)->path();
}

TEST(BuildInfoCli, InfoRejectsFilesThatAreNotTsp) {
  if (!fs::exists(katrina_file())) GTEST_SKIP() << "shared data absent: " << katrina_file();
  const fs::path dir = tsptest::temp_dir();
  std::ofstream(dir / "text.tsp") << "hello\n";
  auto r = run_tspplay("info " + q(dir / "text.tsp"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not an HDF5 file"), std::string::npos) << r.err;
  r = run_tspplay("info " + q(katrina_file()));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not a tspplay .tsp file"), std::string::npos) << r.err;
  r = run_tspplay("info " + q(dir / "none.tsp") + " --json");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("does not exist"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(BuildCli, Compress) {
  const fs::path dir = tsptest::temp_dir();
  ASSERT_EQ(run_tspplay("generate shock --dims 24 --steps 3 -o " + q(dir / "s.h5")).exit_code, 0);
  const auto plain = run_tspplay("build " + q(dir / "s.h5") + " -o " + q(dir / "a.tsp"));
  const auto packed =
      run_tspplay("build " + q(dir / "s.h5") + " --compress deflate:1 -o " + q(dir / "b.tsp"));
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  ASSERT_EQ(packed.exit_code, 0) << packed.err;
  EXPECT_LT(fs::file_size(dir / "b.tsp"), fs::file_size(dir / "a.tsp"));
  const auto info = run_tspplay("info " + q(dir / "b.tsp"));
  EXPECT_NE(info.out.find(", deflate level 1"), std::string::npos) << info.out;
  EXPECT_EQ(run_tspplay("info " + q(dir / "a.tsp")).out.find("deflate"), std::string::npos);
  EXPECT_EQ(run_tspplay("render " + q(dir / "b.tsp") + " --size 32x24 -o " + q(dir / "f")).exit_code,
            0);
  for (const char* bad : {"zstd", "deflate:0", "deflate:10"}) {
    const auto r = run_tspplay("build " + q(dir / "s.h5") + " --compress " + bad + " -o " +
                               q(dir / "c.tsp"));
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.err.find("expected none, deflate or deflate:L"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "c.tsp"));
  }
}

}  // namespace
