// The .tsp file: writer/reader round trip, brick contents, and rejection of bad files.
#include "tsp/store/tsp_file.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include "support/memory_source.h"
#include "support/paths.h"
#include "support/reader_formula.h"
#include "tsp/build/build.h"
#include "tsp/build/level_filter.h"
#include "tsp/core/error.h"
#include "tsp/store/tsp_layout.h"
#include "tsp/store/tsp_writer.h"

namespace tsp {
namespace {

namespace fs = std::filesystem;
using tsptest::MemorySource;

MemorySource wavy_source(Dims d, int steps) {
  return MemorySource::from_function(d, steps, [](int x, int y, int z, int t) {
    return float(std::sin(0.3 * x + 0.2 * y * (t + 1)) + 0.1 * z - 0.05 * t);
  });
}

std::string built_file(Dims d = {21, 14, 9}, int steps = 5, int brick = 8) {
  MemorySource src = wavy_source(d, steps);
  auto path = (tsptest::temp_dir() / "f.tsp").string();
  BuildOptions opt;
  opt.brick_size = brick;
  opt.field_name = "wave";
  build_tsp_file(src, path, opt);
  return path;
}

// Runs f on the file opened read-write with the HDF5 C API, to damage it on purpose.
template <class F>
void edit_file(const std::string& path, F f) {
  hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  f(file);
  H5Fclose(file);
}

// Overwrites the file's root attribute `name` (which must exist) with v, stored as `type`.
template <class T>
void set_attribute(const std::string& path, const char* name, hid_t type, const T& v) {
  edit_file(path, [&](hid_t f) {
    hid_t a = H5Aopen(f, name, H5P_DEFAULT);
    ASSERT_GE(a, 0) << name;
    H5Awrite(a, type, &v);
    H5Aclose(a);
  });
}

void expect_format_error(const std::string& path, const std::string& needle) {
  try {
    TspFile::open(path);
    ADD_FAILURE() << "opened " << path;
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(TspFile, EveryBrickAtEveryStepIsTheQuantizedSource) {
  for (int brick : {4, 8, 32}) {
    const Dims d{21, 14, 9};
    MemorySource src = wavy_source(d, 5);
    auto path = built_file(d, 5, brick);
    auto f = TspFile::open(path);
    const TspTree& tree = f->tree();
    const Quantizer q{tree.value_range()};
    const Octree& o = tree.octree();
    for (int b = 0; b < o.brick_count(); ++b) {
      const Box s = o.brick_samples(b);
      std::vector<std::uint16_t> codes(std::size_t(s.count()));
      for (int t = 0; t < 5; ++t) {
        f->read_brick(b, t, codes);
        std::size_t i = 0;
        for (int z = s.lo[2]; z < s.hi[2]; ++z)
          for (int y = s.lo[1]; y < s.hi[1]; ++y)
            for (int x = s.lo[0]; x < s.hi[0]; ++x, ++i)
              ASSERT_EQ(codes[i], q.encode(src.at(x, y, z, t)))
                  << "B=" << brick << " brick " << b << " step " << t << " at " << x << "," << y
                  << "," << z;
      }
    }
  }
}

TEST(TspFile, MetadataAndShapeRoundTrip) {
  const Dims d{21, 14, 9};
  MemorySource src = wavy_source(d, 5);
  auto f = TspFile::open(built_file(d, 5, 8));
  const TspTree& tree = f->tree();
  TspTree fresh(d, 5, 8);
  EXPECT_EQ(tree.size(), fresh.size());
  EXPECT_EQ(tree.octree().size(), fresh.octree().size());
  EXPECT_EQ(tree.octree().dims(), d);
  EXPECT_EQ(tree.time().steps(), 5);
  EXPECT_EQ(f->metadata().field, "wave");
  EXPECT_EQ(f->metadata().source, src.describe());
  EXPECT_EQ(f->metadata().created_by, "tspplay " TSPPLAY_VERSION);
  EXPECT_EQ(f->metadata().nonfinite_count, 0);
  float lo = INFINITY, hi = -INFINITY;
  for (int t = 0; t < 5; ++t)
    for (int z = 0; z < d.z; ++z)
      for (int y = 0; y < d.y; ++y)
        for (int x = 0; x < d.x; ++x) {
          lo = std::min(lo, src.at(x, y, z, t));
          hi = std::max(hi, src.at(x, y, z, t));
        }
  EXPECT_EQ(f->metadata().data_range, (ValueRange{lo, hi}));
  EXPECT_EQ(tree.value_range(), (ValueRange{lo, hi}));
  std::uint64_t total = 0;
  for (auto c : f->metadata().histogram) total += c;
  EXPECT_EQ(total, std::uint64_t(d.count() * 5));
}

TEST(TspFile, WriterReaderRoundTripIsExact) {
  TspTree tree({30, 9, 17}, 7, 8);
  tree.set_value_range({-3.25, 11.5});
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int i = 0; i < tree.size(); ++i) {
    NodeStats& s = tree.stats(i);
    // Random but valid statistics (the reader refuses min > max, σ < 0, negative errors).
    const float a = float(u(rng)), c = float(u(rng));
    const float lo = std::min(a, c), hi = std::max(a, c);
    const double mean = lo + (hi - lo) * (u(rng) + 10) / 20;
    s = {mean, std::fabs(u(rng)), lo, hi, float(std::fabs(u(rng))), float(std::fabs(u(rng)))};
  }
  TspMetadata meta;
  meta.source = "ünïcode source";
  meta.field = "T";
  meta.data_range = {-4, 12};
  meta.nonfinite_count = 17;
  meta.histogram.assign(kHistogramBins, 0);
  for (int i = 0; i < kHistogramBins; ++i) meta.histogram[i] = std::uint64_t(i) * 1000003u;
  meta.created_by = "test";
  auto path = (tsptest::temp_dir() / "w.tsp").string();
  const auto shape = stored_brick_shape(tree.octree());
  const std::size_t per_brick = std::size_t(7) * shape[0] * shape[1] * shape[2];
  {
    TspWriter w(path, tree);
    for (int b = 0; b < tree.octree().brick_count(); ++b) {
      std::vector<std::uint16_t> codes(per_brick);
      for (std::size_t i = 0; i < per_brick; ++i) codes[i] = std::uint16_t(b * 131 + i * 7);
      w.write_brick_series(b, codes);
    }
    w.finish(tree, meta);
  }
  auto f = TspFile::open(path);
  for (int i = 0; i < tree.size(); ++i) {
    const NodeStats &a = tree.stats(i), &b = f->tree().stats(i);
    ASSERT_EQ(a.mean, b.mean);
    ASSERT_EQ(a.std, b.std);
    ASSERT_EQ(a.min, b.min);
    ASSERT_EQ(a.max, b.max);
    ASSERT_EQ(a.spatial_error, b.spatial_error);
    ASSERT_EQ(a.temporal_error, b.temporal_error);
  }
  EXPECT_EQ(f->tree().value_range(), tree.value_range());
  EXPECT_EQ(f->metadata().source, meta.source);
  EXPECT_EQ(f->metadata().field, meta.field);
  EXPECT_EQ(f->metadata().data_range, meta.data_range);
  EXPECT_EQ(f->metadata().nonfinite_count, 17);
  EXPECT_EQ(f->metadata().histogram, meta.histogram);
  // read_brick returns the unpadded corner [Bz', By', Bx'] of the stored padded brick.
  const Octree& o = tree.octree();
  for (int b : {0, o.brick_count() - 1}) {
    const Box s = o.brick_samples(b);
    std::vector<std::uint16_t> got(std::size_t(s.count()));
    f->read_brick(b, 6, got);
    std::size_t i = 0;
    for (int z = 0; z < s.size(2); ++z)
      for (int y = 0; y < s.size(1); ++y)
        for (int x = 0; x < s.size(0); ++x, ++i) {
          std::size_t k = std::size_t(6) * shape[0] * shape[1] * shape[2] + x +
                          std::size_t(shape[0]) * (y + std::size_t(shape[1]) * z);
          ASSERT_EQ(got[i], std::uint16_t(b * 131 + k * 7));
        }
  }
}

TEST(TspFile, EdgeBricksArePaddedByRepeatingTheLastSample) {
  auto path = built_file({21, 14, 9}, 2, 8);
  auto f = TspFile::open(path);
  const Octree& o = f->tree().octree();
  // x: 20 cells in 3 bricks of 7 → the upper corner brick holds samples [14,21): 7 of 8.
  const int b = o.brick_count() - 1;
  const Box s = o.brick_samples(b);
  const auto shape = stored_brick_shape(o);
  ASSERT_EQ(shape, (std::array<int, 3>{8, 8, 5}));
  ASSERT_LT(s.size(0), shape[0]);
  std::vector<std::uint16_t> unpadded(std::size_t(s.count()));
  f->read_brick(b, 1, unpadded);
  hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t ds = H5Dopen2(file, "/bricks/data", H5P_DEFAULT);
  hsize_t start[5] = {hsize_t(b), 1, 0, 0, 0};
  hsize_t count[5] = {1, 1, hsize_t(shape[2]), hsize_t(shape[1]), hsize_t(shape[0])};
  hid_t fs = H5Dget_space(ds);
  H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, nullptr, count, nullptr);
  hid_t ms = H5Screate_simple(3, count + 2, nullptr);
  std::vector<std::uint16_t> padded(std::size_t(shape[0]) * shape[1] * shape[2]);
  ASSERT_GE(H5Dread(ds, H5T_NATIVE_UINT16, ms, fs, H5P_DEFAULT, padded.data()), 0);
  H5Sclose(ms);
  H5Sclose(fs);
  H5Dclose(ds);
  H5Fclose(file);
  for (int z = 0; z < shape[2]; ++z)
    for (int y = 0; y < shape[1]; ++y)
      for (int x = 0; x < shape[0]; ++x) {
        int cx = std::min(x, s.size(0) - 1), cy = std::min(y, s.size(1) - 1),
            cz = std::min(z, s.size(2) - 1);
        ASSERT_EQ(padded[x + shape[0] * (y + shape[1] * z)],
                  unpadded[cx + s.size(0) * (cy + s.size(1) * cz)]);
      }
}

TEST(TspFile, ReadBrickIsThreadSafe) {
  auto path = built_file({40, 33, 20}, 3, 8);
  auto f = TspFile::open(path);
  const Octree& o = f->tree().octree();
  // Reference reads on one thread, then the same reads from four threads at once.
  std::vector<std::vector<std::uint16_t>> want(o.brick_count());
  for (int b = 0; b < o.brick_count(); ++b) {
    want[b].resize(std::size_t(o.brick_samples(b).count()));
    f->read_brick(b, 2, want[b]);
  }
  std::atomic<int> mismatches{0};
  std::vector<std::thread> threads;
  for (int k = 0; k < 4; ++k)
    threads.emplace_back([&, k] {
      for (int rep = 0; rep < 5; ++rep)
        for (int b = k; b < o.brick_count(); b += 2) {
          std::vector<std::uint16_t> got(want[b].size());
          f->read_brick(b, 2, got);
          if (got != want[b]) ++mismatches;
        }
    });
  for (auto& t : threads) t.join();
  EXPECT_EQ(mismatches, 0);
}

TEST(TspFile, RejectsOtherVersions) {
  auto path = built_file();
  set_attribute(path, "version", H5T_NATIVE_INT, int{kTspFormatVersion + 1});
  expect_format_error(path, "version " + std::to_string(kTspFormatVersion + 1));
}

TEST(TspFile, AVersionOneFileSaysToRebuild) {
  auto path = built_file();
  set_attribute(path, "version", H5T_NATIVE_INT, int{1});
  expect_format_error(path, "format version 1, this tspplay reads versions 2 and 3 only; rebuild");
}

// Level bricks read back as the level filter of the source (quantized), and their residuals as
// stored; a bad level dataset is refused naming it.
TEST(TspFile, LevelBricksAreTheFilteredSourceAndBadLevelDataIsRefused) {
  const Dims d{21, 14, 9};
  MemorySource src = wavy_source(d, 5);
  auto path = (tsptest::temp_dir() / "levels.tsp").string();
  BuildOptions opt;
  opt.brick_size = 8;
  build_tsp_file(src, path, opt);
  {
    auto f = TspFile::open(path);
    const Octree& o = f->tree().octree();
    ASSERT_GT(o.level_brick_count(), 0);
    const Quantizer q{f->tree().value_range()};
    
    std::vector<float> want;
    for (int i = o.brick_count(); i < o.stored_brick_count(); ++i)
      for (int t : {0, 4}) {
        const BrickLattice l = o.lattice(i);
        std::vector<std::uint16_t> got(std::size_t(l.count()));
        f->read_brick(i, t, got);
        std::vector<float> step(std::size_t(d.count()));
        src.read_step(t, step);
        filter_level(step, d, l, std::nullopt, want);
        for (std::size_t k = 0; k < got.size(); ++k)
          ASSERT_EQ(got[k], q.encode(want[k])) << "level brick " << i << " step " << t;
        EXPECT_GT(f->tree().level_error(o.stored_brick_node(i), t), 0.f);
      }
  }
  const auto copy = [&](const std::string& name) {
    const auto p = (tsptest::temp_dir() / name).string();
    fs::copy_file(path, p, fs::copy_options::overwrite_existing);
    return p;
  };
  auto bad_error = copy("bad_error.tsp");
  edit_file(bad_error, [](hid_t f) {
    hid_t ds = H5Dopen2(f, "/levels/error", H5P_DEFAULT);
    float v = -1;
    hid_t space = H5Dget_space(ds);
    hsize_t start[2] = {0, 0}, count[2] = {1, 1};
    H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr);
    hid_t mem = H5Screate_simple(2, count, nullptr);
    H5Dwrite(ds, H5T_NATIVE_FLOAT, mem, space, H5P_DEFAULT, &v);
    H5Sclose(mem);
    H5Sclose(space);
    H5Dclose(ds);
  });
  expect_format_error(bad_error, "/levels/error");
  auto no_lattice = copy("no_lattice.tsp");
  edit_file(no_lattice, [](hid_t f) { H5Ldelete(f, "/levels/lattice", H5P_DEFAULT); });
  expect_format_error(no_lattice, "/levels/lattice");
}

TEST(TspFile, RejectsAnotherFormatTag) {
  auto path = built_file();
  edit_file(path, [](hid_t f) { H5Adelete(f, "format"); });
  expect_format_error(path, "not a tspplay");
}

TEST(TspFile, RejectsMissingDataset) {
  auto path = built_file();
  edit_file(path, [](hid_t f) { H5Ldelete(f, "/stats/temporal_error", H5P_DEFAULT); });
  expect_format_error(path, "/stats/temporal_error: missing");
}

TEST(TspFile, RejectsInconsistentShape) {
  auto path = built_file();
  edit_file(path, [](hid_t f) {
    H5Ldelete(f, "/octree/level", H5P_DEFAULT);
    hsize_t n = 3;
    hid_t sp = H5Screate_simple(1, &n, nullptr);
    hid_t ds =
        H5Dcreate2(f, "/octree/level", H5T_STD_I32LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dclose(ds);
    H5Sclose(sp);
  });
  expect_format_error(path, "/octree/level: expected shape");
}

TEST(TspFile, RejectsWrongTreeContents) {
  auto path = built_file();
  edit_file(path, [](hid_t f) {
    hid_t ds = H5Dopen2(f, "/octree/parent", H5P_DEFAULT);
    std::vector<int> parent(std::size_t(TspTree({21, 14, 9}, 5, 8).octree().size()), 0);
    H5Dwrite(ds, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, parent.data());
    H5Dclose(ds);
  });
  expect_format_error(path, "/octree/parent: element 0");
}

TEST(TspFile, RejectsBadBrickSizeAttribute) {
  auto path = built_file();
  set_attribute(path, "brick_size", H5T_NATIVE_INT, int{12});
  expect_format_error(path, "brick size 12");
}

TEST(TspFile, RejectsTruncatedFile) {
  auto path = built_file({40, 33, 20}, 4, 8);
  auto size = fs::file_size(path);
  fs::resize_file(path, size / 2);
  EXPECT_THROW(TspFile::open(path), FormatError);
}

TEST(TspFile, RejectsNonHdf5AndMissingFiles) {
  auto dir = tsptest::temp_dir();
  auto text = (dir / "note.tsp").string();
  std::ofstream(text) << "this is not HDF5\n";
  expect_format_error(text, "not an HDF5 file");
  EXPECT_THROW(TspFile::open((dir / "none.tsp").string()), IoError);
  EXPECT_THROW(TspFile::open(dir.string()), IoError);
}

TEST(TspFile, FailingSourceLeavesNoOutputAndNoTempFile) {
  auto dir = tsptest::temp_dir();
  auto path = (dir / "out.tsp").string();
  MemorySource src = wavy_source({20, 20, 20}, 6);
  src.set_fail_at(3);
  BuildOptions opt;
  opt.brick_size = 8;
  EXPECT_THROW(build_tsp_file(src, path, opt), IoError);
  EXPECT_TRUE(fs::is_empty(dir)) << fs::directory_iterator(dir)->path();
  // An existing file at the output path survives a failed rebuild unchanged.
  MemorySource good = wavy_source({20, 20, 20}, 2);
  build_tsp_file(good, path, opt);
  const std::string before = tsptest::read_file(path);
  EXPECT_THROW(build_tsp_file(src, path, opt), IoError);
  EXPECT_EQ(tsptest::read_file(path), before);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  EXPECT_NO_THROW(TspFile::open(path));
}

TEST(TspFile, ProgressCallbackCanCancelInEitherPass) {
  for (const std::string cancel_in : {"reading", "bricks"}) {
    auto dir = tsptest::temp_dir();
    MemorySource src = wavy_source({20, 20, 20}, 4);
    BuildOptions opt;
    opt.brick_size = 8;
    opt.threads = 2;
    opt.progress = [&](const std::string& phase, std::int64_t, std::int64_t) {
      if (phase == cancel_in) throw Error("cancelled");
    };
    EXPECT_THROW(build_tsp_file(src, (dir / "out.tsp").string(), opt), Error) << cancel_in;
    EXPECT_TRUE(fs::is_empty(dir)) << cancel_in;
  }
}

// Hostile files: sizes beyond the limits, impossible statistics and counts are refused on open
// (before anything is allocated for them), and a corrupted brick is reported by its index and
// step through the chunks' Fletcher-32 checksums.
TEST(TspFile, HugeDimsOrStepsAreRefusedBeforeAllocating) {
  for (auto [attr, values] : {std::pair{"dims", std::vector<int>{2000000000, 2000000000, 9}},
                              std::pair{"steps", std::vector<int>{2000000000}}}) {
    auto path = built_file();
    edit_file(path, [&, attr = attr, values = values](hid_t f) {
      hid_t a = H5Aopen(f, attr, H5P_DEFAULT);
      H5Awrite(a, H5T_NATIVE_INT, values.data());
      H5Aclose(a);
    });
    expect_format_error(path, "expected");
  }
}

TEST(TspFile, ImpossibleStatisticsAndCountsAreRefused) {
  struct Damage {
    const char* dataset;
    double value;
    const char* needle;
  };
  for (const Damage& d : {Damage{"/stats/mean", NAN, "statistics of TSP node 3"},
                          Damage{"/stats/std", -1.0, "statistics of TSP node 3"},
                          Damage{"/stats/min", 1e9, "statistics of TSP node 3"},
                          Damage{"/stats/spatial_error", -0.5, "statistics of TSP node 3"}}) {
    auto path = built_file();
    edit_file(path, [&](hid_t f) {
      hid_t ds = H5Dopen2(f, d.dataset, H5P_DEFAULT);
      ASSERT_GE(ds, 0) << d.dataset;
      hid_t space = H5Dget_space(ds);
      hsize_t start = 3, count = 1;
      H5Sselect_hyperslab(space, H5S_SELECT_SET, &start, nullptr, &count, nullptr);
      hid_t mem = H5Screate_simple(1, &count, nullptr);
      H5Dwrite(ds, H5T_NATIVE_DOUBLE, mem, space, H5P_DEFAULT, &d.value);
      H5Sclose(mem);
      H5Sclose(space);
      H5Dclose(ds);
    });
    expect_format_error(path, d.needle);
  }
  auto path = built_file();
  set_attribute(path, "nonfinite_count", H5T_NATIVE_INT64, std::int64_t{-4});
  expect_format_error(path, "nonfinite_count");
}

TEST(TspFile, CorruptedBrickIsReportedByIndexAndStep) {
  auto path = built_file({21, 14, 9}, 5, 8);
  // Flip one byte in the middle of the chunk of brick 2 at step 3.
  haddr_t addr = 0;
  hsize_t size = 0;
  edit_file(path, [&](hid_t f) {
    hid_t ds = H5Dopen2(f, "/bricks/data", H5P_DEFAULT);
    hsize_t offset[5] = {2, 3, 0, 0, 0};
    unsigned mask = 0;
    ASSERT_GE(H5Dget_chunk_info_by_coord(ds, offset, &mask, &addr, &size), 0);
    H5Dclose(ds);
  });
  ASSERT_GT(size, 8u);
  {
    std::fstream io(path, std::ios::in | std::ios::out | std::ios::binary);
    io.seekg(std::streamoff(addr + size / 2));
    char c = 0;
    io.read(&c, 1);
    c = char(c ^ 0x5a);
    io.seekp(std::streamoff(addr + size / 2));
    io.write(&c, 1);
  }
  auto f = TspFile::open(path);  // metadata is intact
  std::vector<std::uint16_t> codes(std::size_t(f->tree().octree().brick_samples(2).count()));
  EXPECT_NO_THROW(f->read_brick(2, 2, codes));
  try {
    f->read_brick(2, 3, codes);
    FAIL() << "a corrupted brick was read";
  } catch (const FormatError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("brick 2 at step 3"), std::string::npos) << m;
    EXPECT_NE(m.find("checksum"), std::string::npos) << m;
  }
}

TEST(TspFile, SpacingsThatCannotBeDrawnAreRefused) {
  // A denormal, or two normal spacings 1e600 apart: every frame would be blank.
  for (const std::array<double, 3>& sp : {std::array<double, 3>{5e-324, 1, 1},
                                          std::array<double, 3>{1e300, 1e-300, 1},
                                          std::array<double, 3>{1, 0, 1}}) {
    auto path = built_file();
    edit_file(path, [&](hid_t f) {
      hid_t a = H5Aopen(f, "spacing", H5P_DEFAULT);
      ASSERT_GE(a, 0);
      H5Awrite(a, H5T_NATIVE_DOUBLE, sp.data());
      H5Aclose(a);
    });
    expect_format_error(path, "spacing");
  }
}

TEST(TspFile, APresentBrickWithoutAChunkIsAFormatErrorNotZeros) {
  // The data set rewritten without the chunk of brick 2 at step 3: HDF5 would read its fill
  // value (zeros) as if it were data.
  auto path = built_file({21, 14, 9}, 5, 8);
  edit_file(path, [&](hid_t f) {
    hid_t ds = H5Dopen2(f, "/bricks/data", H5P_DEFAULT);
    hid_t space = H5Dget_space(ds), dcpl = H5Dget_create_plist(ds);
    hsize_t dims[5];
    H5Sget_simple_extent_dims(space, dims, nullptr);
    std::vector<std::uint16_t> all(std::size_t(dims[0] * dims[1] * dims[2] * dims[3] * dims[4]));
    ASSERT_GE(H5Dread(ds, H5T_NATIVE_UINT16, H5S_ALL, H5S_ALL, H5P_DEFAULT, all.data()), 0);
    hid_t copy = H5Dcreate2(f, "/bricks/copy", H5T_STD_U16LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    ASSERT_GE(copy, 0);
    hsize_t count[5] = {1, 1, dims[2], dims[3], dims[4]};
    hid_t mem = H5Screate_simple(3, count + 2, nullptr);
    const std::size_t per = std::size_t(dims[2] * dims[3] * dims[4]);
    for (hsize_t b = 0; b < dims[0]; ++b)
      for (hsize_t t = 0; t < dims[1]; ++t) {
        if (b == 2 && t == 3) continue;
        hsize_t start[5] = {b, t, 0, 0, 0};
        H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr);
        ASSERT_GE(H5Dwrite(copy, H5T_NATIVE_UINT16, mem, space, H5P_DEFAULT,
                           all.data() + (b * dims[1] + t) * per), 0);
      }
    H5Sclose(mem);
    H5Dclose(copy);
    H5Pclose(dcpl);
    H5Sclose(space);
    H5Dclose(ds);
    ASSERT_GE(H5Ldelete(f, "/bricks/data", H5P_DEFAULT), 0);
    ASSERT_GE(H5Lmove(f, "/bricks/copy", f, "/bricks/data", H5P_DEFAULT, H5P_DEFAULT), 0);
  });
  auto f = TspFile::open(path);
  std::vector<std::uint16_t> codes(std::size_t(f->tree().octree().brick_samples(2).count()));
  EXPECT_NO_THROW(f->read_brick(2, 2, codes));
  const std::string m = tsptest::error_of<FormatError>([&] { f->read_brick(2, 3, codes); });
  EXPECT_NE(m.find("brick 2 at step 3"), std::string::npos) << m;
  EXPECT_NE(m.find("no stored chunk"), std::string::npos) << m;
  EXPECT_NE(m.find(path), std::string::npos) << m;
}

}  // namespace
}  // namespace tsp
