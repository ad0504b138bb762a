// Typed HDF5 access on the committed fixtures (tests/data/h5, written by h5py): type names,
// numeric-only datasets, numeric and string attributes, exact-float conversion, and volume
// slabs read directly and through a batch converter, checked against the fixtures' formula.
#include "tsp/hdf5/hdf5_values.h"

#include <gtest/gtest.h>

#include <vector>

#include "support/paths.h"
#include "support/reader_formula.h"
#include "tsp/core/error.h"
#include "tsp/hdf5/hdf5_handle.h"

namespace {

using namespace tsp::io;
using tsp::h5::Handle;

Handle open_dataset(const Handle& file, const char* name) {
  Handle d(H5Dopen2(file.get(), name, H5P_DEFAULT));
  EXPECT_TRUE(bool(d)) << name;
  return d;
}

Handle fixture(const char* name) {
  tsp::h5::silence_errors();
  return tsp::h5::open_file_readonly((tsptest::test_data_dir() / "h5" / name).string());
}

TEST(Hdf5Values, NamesTypesAndAcceptsOnlyNumericDatasets) {
  Handle grid = fixture("grid4d.h5"), ints = fixture("int16.h5"), bad = fixture("bad_types.h5");
  Handle f = open_dataset(grid, "/f"), i16 = open_dataset(ints, "/plain"),
         u64 = open_dataset(ints, "/u64"), text = open_dataset(bad, "/text"),
         compound = open_dataset(bad, "/compound");
  auto type_of = [](const Handle& d) { return Handle(H5Dget_type(d.get())); };
  EXPECT_EQ(describe_h5_type(type_of(f).get()), "32-bit float");
  EXPECT_EQ(describe_h5_type(type_of(i16).get()), "16-bit signed integer");
  EXPECT_EQ(describe_h5_type(type_of(u64).get()), "64-bit unsigned integer");
  EXPECT_EQ(describe_h5_type(type_of(text).get()), "string");
  EXPECT_EQ(describe_h5_type(type_of(compound).get()), "compound");
  EXPECT_NO_THROW(require_numeric_dataset(f.get(), "grid4d.h5, dataset /f"));
  EXPECT_NO_THROW(require_numeric_dataset(u64.get(), "u64"));
  try {
    require_numeric_dataset(text.get(), "bad_types.h5, dataset /text");
    FAIL() << "no error";
  } catch (const tsp::FormatError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("bad_types.h5, dataset /text"), std::string::npos) << m;
    EXPECT_NE(m.find("string"), std::string::npos) << m;
  }
  EXPECT_THROW(require_numeric_dataset(compound.get(), "c"), tsp::FormatError);
  EXPECT_TRUE(converts_exactly_to_float(f.get()));
  EXPECT_TRUE(converts_exactly_to_float(i16.get()));
  EXPECT_FALSE(converts_exactly_to_float(u64.get()));
}

TEST(Hdf5Values, NumericAndStringAttributes) {
  Handle ints = fixture("int16.h5"), bad = fixture("bad_types.h5");
  Handle packed = open_dataset(ints, "/packed"), bad_scale = open_dataset(bad, "/bad_scale");
  EXPECT_EQ(numeric_attribute(packed.get(), "scale_factor", "p"), (std::vector<double>{0.5}));
  EXPECT_EQ(numeric_attribute(packed.get(), "add_offset", "p"), (std::vector<double>{100}));
  EXPECT_FALSE(numeric_attribute(packed.get(), "no_such", "p").has_value());
  EXPECT_THROW(numeric_attribute(bad_scale.get(), "scale_factor", "bad_types.h5 /bad_scale"),
               tsp::FormatError);
  EXPECT_TRUE(string_attribute(bad_scale.get(), "scale_factor", "s").has_value());
  EXPECT_THROW(string_attribute(packed.get(), "scale_factor", "p"), tsp::FormatError);
  // VTKHDF's Type: variable length in one fixture, fixed length (padded) in the other.
  for (const char* name : {"vtkhdf_static.hdf", "vtkhdf_transient.hdf"}) {
    Handle file = fixture(name);
    Handle group(H5Gopen2(file.get(), "/VTKHDF", H5P_DEFAULT));
    ASSERT_TRUE(bool(group));
    EXPECT_EQ(string_attribute(group.get(), "Type", name), "ImageData") << name;
  }
}

TEST(Hdf5Values, ReadsOneStepOfAVolumeDirectlyAndInBatches) {
  Handle grid = fixture("grid4d.h5");
  Handle f = open_dataset(grid, "/f");
  const tsp::Dims d{5, 4, 3};
  for (int t = 0; t < 3; ++t) {
    VolumeSlab slab{{hsize_t(t)}, {3, 4, 5}, 0};
    std::vector<float> direct(std::size_t(d.count())), batched(direct.size());
    read_volume(f.get(), slab, direct, {}, "grid4d.h5 /f");
    tsptest::expect_formula(direct, d, t);
    std::size_t converted = 0;
    read_volume(
        f.get(), slab, batched,
        [&](std::span<const double> in, std::span<float> out) {
          ASSERT_EQ(in.size(), out.size());
          converted += in.size();
          for (std::size_t i = 0; i < in.size(); ++i) out[i] = float(in[i]) + 1.0f;
        },
        "grid4d.h5 /f");
    EXPECT_EQ(converted, direct.size());
    tsptest::expect_formula(batched, d, t, 1.0f);
  }
}

}  // namespace
