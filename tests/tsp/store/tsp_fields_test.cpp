// Several fields in one .tsp file: each field's tree, statistics and bricks are exactly those of
// a file built from that field alone; the first sits at the root (every reader sees it); fields
// may lie on different grids (their own dims, origin, spacing) inside the file's frame; a field
// with other steps, a repeated name and an unknown field are clear errors.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include "support/memory_source.h"
#include "support/paths.h"
#include "tsp/build/build.h"
#include "tsp/core/error.h"
#include "tsp/store/tsp_file.h"

namespace tsp {
namespace {

namespace fs = std::filesystem;
using tsptest::MemorySource;

constexpr Dims kDims{19, 13, 10};
constexpr int kSteps = 4;

MemorySource field_source(int which, Dims d = kDims) {
  return MemorySource::from_function(d, kSteps, [which](int x, int y, int z, int t) {
    return which == 0 ? float(std::sin(0.3 * x + 0.2 * y * (t + 1)) + 0.1 * z)
         : which == 1 ? float(x * y - 3 * z + 10 * t)
                      : float(std::cos(0.1 * x * z) * (t + 2));
  });
}

BuildOptions options() {
  BuildOptions o;
  o.brick_size = 8;
  return o;
}

std::string single(int which, const std::string& name) {
  MemorySource src = field_source(which);
  BuildOptions o = options();
  o.field_name = name;
  const std::string path = (tsptest::temp_dir() / (name + ".tsp")).string();
  build_tsp_file(src, path, o);
  return path;
}

std::string multi(const std::vector<std::string>& names) {
  const std::string path = (tsptest::temp_dir() / "multi.tsp").string();
  build_tsp_fields(
      [&](const std::string& f) -> std::unique_ptr<VolumeSource> {
        const int which = int(std::find(names.begin(), names.end(), f) - names.begin());
        return std::make_unique<MemorySource>(field_source(which));
      },
      names, path, options());
  return path;
}

void expect_same_field(const TspFile& a, const TspFile& b) {
  const TspTree& ta = a.tree();
  const TspTree& tb = b.tree();
  ASSERT_EQ(ta.size(), tb.size());
  EXPECT_EQ(ta.value_range().lo, tb.value_range().lo);
  EXPECT_EQ(ta.value_range().hi, tb.value_range().hi);
  for (int i = 0; i < ta.size(); ++i) {
    EXPECT_EQ(ta.stats(i).mean, tb.stats(i).mean) << i;
    EXPECT_EQ(ta.stats(i).std, tb.stats(i).std) << i;
    EXPECT_EQ(ta.stats(i).spatial_error, tb.stats(i).spatial_error) << i;
    EXPECT_EQ(ta.stats(i).temporal_error, tb.stats(i).temporal_error) << i;
  }
  EXPECT_EQ(a.metadata().histogram, b.metadata().histogram);
  EXPECT_TRUE(std::equal(ta.level_errors().begin(), ta.level_errors().end(),
                         tb.level_errors().begin(), tb.level_errors().end()));
  const Octree& o = ta.octree();
  for (int brick = 0; brick < o.stored_brick_count(); ++brick)
    for (int t = 0; t < kSteps; ++t) {
      std::vector<std::uint16_t> x(std::size_t(o.lattice(brick).count())), y(x.size());
      a.read_brick(brick, t, x);
      b.read_brick(brick, t, y);
      ASSERT_EQ(x, y) << "brick " << brick << " step " << t;
    }
}

TEST(TspFields, EachFieldIsTheSingleFieldBuildOfItsSource) {
  const std::vector<std::string> names = {"wave", "ramp", "ripple"};
  const std::string path = multi(names);
  for (std::size_t k = 0; k < names.size(); ++k) {
    auto f = TspFile::open(path, names[k]);
    EXPECT_EQ(f->fields(), names);
    EXPECT_EQ(f->field_index(), int(k));
    EXPECT_EQ(f->metadata().field, names[k]);
    expect_same_field(*f, *TspFile::open(single(int(k), names[k])));
  }
  // No field named: the first, at the root.
  EXPECT_EQ(TspFile::open(path)->metadata().field, "wave");
  // A one-field file lists its one field.
  EXPECT_EQ(TspFile::open(single(1, "ramp"))->fields(), std::vector<std::string>{"ramp"});
}

// A field placed in physical space (WRF's staggered W: one more level, half a layer lower).
class PlacedSource final : public MemorySource {
 public:
  PlacedSource(MemorySource m, std::array<double, 3> origin)
      : MemorySource(std::move(m)), origin_(origin) {}
  std::array<double, 3> origin() const override { return origin_; }

 private:
  std::array<double, 3> origin_;
};

TEST(TspFields, FieldsOnDifferentGridsKeepTheirOwnAndShareAFrame) {
  constexpr Dims kStaggered{20, 13, 11};
  const std::array<double, 3> shift{-0.5, 0, -0.5};
  const std::string path = (tsptest::temp_dir() / "grids.tsp").string();
  build_tsp_fields(
      [&](const std::string& f) -> std::unique_ptr<VolumeSource> {
        if (f == "T") return std::make_unique<MemorySource>(field_source(0));
        return std::make_unique<PlacedSource>(field_source(1, kStaggered), shift);
      },
      {"T", "W"}, path, options());
  auto t = TspFile::open(path, "T");
  auto w = TspFile::open(path, "W");
  EXPECT_EQ(t->tree().octree().dims(), kDims);
  EXPECT_EQ(w->tree().octree().dims(), kStaggered);
  EXPECT_EQ(w->metadata().origin, shift);
  // The frame holds both boxes: T's [0, D − 1], W's [shift, shift + D' − 1].
  const Aabb want{{-0.5, 0, -0.5}, {18.5, 12, 9.5}};
  EXPECT_EQ(t->frame(), want);
  EXPECT_EQ(w->frame(), want);
  // W is exactly its own single-field build.
  PlacedSource alone(field_source(1, kStaggered), shift);
  const std::string single_w = (tsptest::temp_dir() / "w.tsp").string();
  build_tsp_file(alone, single_w, options());
  expect_same_field(*w, *TspFile::open(single_w));
  // A one-field file's frame is its own box.
  EXPECT_EQ(TspFile::open(single_w)->frame(), (Aabb{{-0.5, 0, -0.5}, {18.5, 12, 9.5}}));
}

TEST(TspFields, UnknownFieldOtherStepsAndRepeatedNamesAreErrors) {
  const std::string path = multi({"wave", "ramp"});
  try {
    TspFile::open(path, "pressure");
    FAIL() << "opened";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("holds the field(s) wave, ramp"), std::string::npos)
        << e.what();
  }
  const std::string out = (tsptest::temp_dir() / "bad.tsp").string();
  auto open_other = [](const std::string& f) -> std::unique_ptr<VolumeSource> {
    if (f == "a") return std::make_unique<MemorySource>(field_source(0));
    return std::make_unique<MemorySource>(  // one step fewer
        MemorySource::from_function(kDims, kSteps - 1, [](int x, int, int, int) { return float(x); }));
  };
  EXPECT_THROW(build_tsp_fields(open_other, {"a", "b"}, out, options()), FormatError);
  EXPECT_FALSE(fs::exists(out));
  for (const auto& entry : fs::directory_iterator(fs::path(out).parent_path()))
    EXPECT_EQ(entry.path().filename().string().find(".bad.tsp.tmp"), std::string::npos);
  EXPECT_THROW(build_tsp_fields(open_other, {"a", "a"}, out, options()), UsageError);
  EXPECT_THROW(build_tsp_fields(open_other, {}, out, options()), UsageError);
}

TEST(TspFields, AListedFieldWithoutItsGroupIsAFormatError) {
  const std::string path = multi({"wave", "ramp"});
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  H5Ldelete(f, "fields/1", H5P_DEFAULT);
  H5Fclose(f);
  EXPECT_THROW(TspFile::open(path, "ramp"), FormatError);
  EXPECT_NO_THROW(TspFile::open(path, "wave"));
}

}  // namespace
}  // namespace tsp
