// One .vti file on its own: every encoding the fixtures hold decoded to the formula, field
// resolution (default, by name, cells, vectors refused), header-only parsing, and clear errors
// for unsupported compressors and for a file that is not ImageData.
#include "tsp/source/vtk/vti_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "support/paths.h"
#include "support/reader_formula.h"
#include "tsp/core/error.h"

namespace {

using tsp::io::VtiFile;
using tsptest::error_of;
using tsptest::kFixtureCellDims;
using tsptest::kFixtureDims;

std::string fixture(const std::string& name) {
  return (tsptest::test_data_dir() / "vti" / name).string();
}

TEST(VtiFile, EveryEncodingDecodesToTheFormula) {
  for (const char* v : {"ascii", "binary", "appended_raw", "appended_b64", "zlib_appended",
                        "zlib_binary_be", "pieces"}) {
    for (int t = 0; t < 3; ++t) {
      const VtiFile f(fixture(std::string(v) + "_" + std::to_string(t) + ".vti"), false);
      const tsp::io::VtiField field = f.resolve("");
      EXPECT_EQ(field.name, "f") << v;  // PointData's Scalars
      EXPECT_FALSE(field.cells);
      ASSERT_EQ(f.dims(field), kFixtureDims);
      std::vector<float> out(std::size_t(kFixtureDims.count()));
      f.read(field, out);
      SCOPED_TRACE(std::string(v) + " step " + std::to_string(t));
      tsptest::expect_formula(out, kFixtureDims, t);
      // The Int16 copy holds the same values.
      const tsp::io::VtiField g = f.resolve("g");
      f.read(g, out);
      tsptest::expect_formula(out, kFixtureDims, t);
    }
  }
}

TEST(VtiFile, CellDataHasCellDimsAndVectorsAreRefused) {
  const VtiFile f(fixture("ascii_1.vti"), false);
  const tsp::io::VtiField c = f.resolve("c");
  EXPECT_TRUE(c.cells);
  EXPECT_EQ(f.dims(c), kFixtureCellDims);
  std::vector<float> out(std::size_t(kFixtureCellDims.count()));
  f.read(c, out);
  tsptest::expect_formula(out, kFixtureCellDims, 1);
  const std::string m = error_of<tsp::FormatError>([&] { f.resolve("v"); });
  EXPECT_NE(m.find("ascii_1.vti"), std::string::npos) << m;
  EXPECT_NE(m.find("component"), std::string::npos) << m;
  const std::string missing = error_of<tsp::FormatError>([&] { f.resolve("nope"); });
  // The error lists what the file has.
  for (const char* name : {"f", "g", "v", "c"})
    EXPECT_NE(missing.find(name), std::string::npos) << missing;
}

TEST(VtiFile, HeaderOnlyKnowsTheGridAndTheArrays) {
  for (const char* v : {"appended_raw_2.vti", "appended_b64_0.vti", "zlib_appended_1.vti"}) {
    const VtiFile f(fixture(v), true);
    EXPECT_EQ(f.dims(f.resolve("")), kFixtureDims) << v;
    EXPECT_EQ(f.dims(f.resolve("c")), kFixtureCellDims) << v;
  }
}

TEST(VtiFile, UnsupportedCompressorAndWrongKindAreFormatErrors) {
  const std::string lz4 = error_of<tsp::FormatError>([] { VtiFile(fixture("lz4.vti"), false); });
  EXPECT_NE(lz4.find("lz4.vti"), std::string::npos) << lz4;
  EXPECT_NE(lz4.find("LZ4"), std::string::npos) << lz4;
  const auto dir = tsptest::temp_dir();
  const auto poly = (dir / "poly.vti").string();
  std::ofstream(poly) << "<VTKFile type=\"PolyData\" version=\"0.1\"><PolyData/></VTKFile>\n";
  const std::string kind = error_of<tsp::FormatError>([&] { VtiFile(poly, false); });
  EXPECT_NE(kind.find("poly.vti"), std::string::npos) << kind;
  EXPECT_NE(kind.find("ImageData"), std::string::npos) << kind;
  const std::string none =
      error_of<tsp::IoError>([&] { VtiFile((dir / "none.vti").string(), false); });
  EXPECT_NE(none.find("none.vti"), std::string::npos) << none;
}

}  // namespace
