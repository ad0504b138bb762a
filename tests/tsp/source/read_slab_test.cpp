// VolumeSource::read_slab against read_step for every reader that reads slabs (HDF5 3-D, 4-D,
// per-step groups, packed and converted integers; VTKHDF image data, static and transient; raw files in both byte orders; the built-in
// generators): every slab of every step holds exactly the planes the whole step holds.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "support/paths.h"
#include "support/reader_formula.h"
#include "tsp/core/error.h"
#include "tsp/source/open_source.h"
#include "tsp/source/procedural/generate.h"

namespace tsp {
namespace {

namespace fs = std::filesystem;

void expect_slabs_match_steps(VolumeSource& s, const std::string& what) {
  ASSERT_TRUE(s.reads_slabs()) << what;
  const Dims d = s.dims();
  const std::int64_t plane = std::int64_t(d.x) * d.y;
  std::vector<float> whole(std::size_t(d.count()));
  for (int t = 0; t < s.steps(); ++t) {
    s.read_step(t, whole);
    for (int z0 = 0; z0 < d.z; ++z0)
      for (int z1 = z0 + 1; z1 <= d.z; ++z1) {
        std::vector<float> slab(std::size_t((z1 - z0) * plane), -12345.f);
        s.read_slab(t, z0, z1, slab);
        ASSERT_EQ(std::memcmp(slab.data(), whole.data() + z0 * plane, slab.size() * sizeof(float)),
                  0)
            << what << " step " << t << " planes " << z0 << ".." << z1;
      }
  }
}

TEST(ReadSlab, Hdf5DatasetsOfEveryLayoutAndType) {
  for (const auto& [file, field] : std::vector<std::pair<std::string, std::string>>{
           {"grid4d.h5", "f"},
           {"grid4d.h5", "single"},
           {"group_steps.h5", "steps"},
           {"int16.h5", "packed"},
           {"int16.h5", "u64"},
           {"vtkhdf_static.hdf", ""},
           {"vtkhdf_transient.hdf", ""}}) {
    auto s = tsptest::open_field(tsptest::h5_fixture(file), field);
    expect_slabs_match_steps(*s, file + " " + field);
  }
}

// A chunked, compressed dataset (what `tspplay generate` writes: chunks of whole planes, as
// deep as 4 MiB allows) reads its slabs like its steps and tells its chunks' depth, so a build
// reads each chunk once; a contiguous one has no preferred height.
TEST(ReadSlab, ChunkedDatasetsTellTheirChunkDepth) {
  const fs::path dir = tsptest::temp_dir();
  GenerateOptions o;
  o.dims = Dims{64, 32, 12};  // 8 KiB planes: chunks of 12 planes, the whole step (< 4 MiB)
  o.steps = 2;
  auto gen = make_generated_source("shock", o);
  write_generated_dataset(*gen, (dir / "g.h5").string(), 4);
  auto s = tsptest::open_field((dir / "g.h5").string(), "shock");
  EXPECT_EQ(s->slab_alignment(), 12);
  expect_slabs_match_steps(*s, "gzip chunks");
  EXPECT_EQ(tsptest::open_field(tsptest::h5_fixture("grid4d.h5"), "f")->slab_alignment(), 0);
}

TEST(ReadSlab, RawFilesInBothByteOrdersAndAShortFileNamed) {
  const fs::path dir = tsptest::temp_dir();
  const Dims d{5, 4, 6};
  for (bool big : {false, true}) {
    const std::string tag = big ? "be" : "le";
    for (int t = 0; t < 2; ++t) {
      std::ofstream out(dir / ("r" + tag + "_" + std::to_string(t) + ".raw"), std::ios::binary);
      for (std::int64_t i = 0; i < d.count(); ++i) {
        std::uint16_t v = std::uint16_t(i * 7 + t * 1000);
        if (big) v = std::uint16_t((v >> 8) | (v << 8));
        out.write(reinterpret_cast<const char*>(&v), 2);
      }
    }
    SourceOptions o;
    o.raw_dims = d;
    o.raw_type = RawType::u16;
    o.raw_big_endian = big;
    auto s = open_source((dir / ("r" + tag + "_%d.raw")).string(), o);
    expect_slabs_match_steps(*s, "raw " + tag);
  }
  // A file cut short after opening: a slab read names the file and its size, even for planes the
  // short file still holds.
  SourceOptions o;
  o.raw_dims = d;
  o.raw_type = RawType::u16;
  auto s = open_source((dir / "rle_%d.raw").string(), o);
  fs::resize_file(dir / "rle_1.raw", 100);
  std::vector<float> slab(std::size_t(d.x) * d.y);
  const std::string msg = tsptest::error_of<FormatError>([&] { s->read_slab(1, 0, 1, slab); });
  EXPECT_NE(msg.find("rle_1.raw: holds 100 bytes, expected 240"), std::string::npos) << msg;
}

TEST(ReadSlab, GeneratedDatasetsWhateverTheThreadCount) {
  for (const std::string name : {"shock", "vortex"}) {
    GenerateOptions o;
    o.dims = Dims{9, 7, 11};
    o.steps = 2;
    o.threads = 3;
    auto s = make_generated_source(name, o);
    expect_slabs_match_steps(*s, name);
  }
}

}  // namespace
}  // namespace tsp
