#include "tsp/source/vti_source.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "support/paths.h"
#include "support/reader_formula.h"
#include "tsp/core/error.h"

namespace tsp {
namespace {

namespace fs = std::filesystem;
using namespace tsptest;  // the reader fixtures' formula, grids and helpers

fs::path vti_dir() {
  return tsptest::test_data_dir() / "vti";
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

// Copy of a fixture with one substring replaced (the replacement must keep binary offsets:
// same length, or in the XML header before any appended data).
fs::path patched(const std::string& fixture, const std::string& from, const std::string& to) {
  std::string text = slurp(vti_dir() / fixture);
  std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  fs::path p = tsptest::temp_dir() / fixture;
  write(p, text);
  return p;
}

// Every encoding VTK's writer produced (see tests/data/make_fixtures.py).
const char* const kVariants[] = {"ascii",         "binary",         "appended_raw", "appended_b64",
                                 "zlib_appended", "zlib_binary_be", "pieces"};

// The fixtures list steps out of order; times 0, 0.25, 0.5 hold f at t = 0, 1, 2.
void expect_series(VolumeSource& s, const std::string& field, Dims d, const std::string& tag) {
  SCOPED_TRACE(tag + " field " + field);
  tsptest::expect_steps(s, d, {0, 1, 2});
}

TEST(VtiSource, PvdInEveryEncodingReadsExactValuesInTimeOrder) {
  for (const char* v : kVariants) {
    fs::path pvd = vti_dir() / (std::string(v) + ".pvd");
    expect_series(*open_field(pvd, "f"), "f", kFixtureDims, v);
    expect_series(*open_field(pvd, "g"), "g", kFixtureDims, v);      // Int16
    expect_series(*open_field(pvd, "c"), "c", kFixtureCellDims, v);  // Float64 cell data
  }
}

TEST(VtiSource, VtiSeriesJsonInEveryEncoding) {
  for (const char* v : kVariants) {
    auto s = open_field(vti_dir() / (std::string(v) + ".vti.series"), "f");
    expect_series(*s, "f", kFixtureDims, v);
  }
}

TEST(VtiSource, FixturesReallyCoverTheEncodings) {
  // Guards the fixture script: the variants must hold what their names say.
  EXPECT_NE(slurp(vti_dir() / "ascii_0.vti").find("format=\"ascii\""), std::string::npos);
  EXPECT_NE(slurp(vti_dir() / "appended_b64_0.vti").find("encoding=\"base64\""), std::string::npos);
  EXPECT_NE(slurp(vti_dir() / "appended_raw_0.vti").find("header_type=\"UInt64\""),
            std::string::npos);
  std::string be = slurp(vti_dir() / "zlib_binary_be_0.vti");
  EXPECT_NE(be.find("BigEndian"), std::string::npos);
  EXPECT_NE(be.find("vtkZLibDataCompressor"), std::string::npos);
  std::string pieces = slurp(vti_dir() / "pieces_0.vti");
  std::size_t n = 0;
  for (std::size_t at = pieces.find("<Piece"); at != std::string::npos;
       at = pieces.find("<Piece", at + 1))
    ++n;
  EXPECT_EQ(n, 3u);
}

TEST(VtiSource, SingleVtiIsOneStepAndDefaultsToActiveScalars) {
  auto s = open_field(vti_dir() / "binary_2.vti", "");
  EXPECT_EQ(s->dims(), kFixtureDims);
  ASSERT_EQ(s->steps(), 1);
  expect_formula(tsptest::read_step(*s, 0), kFixtureDims, 2);
}

TEST(VtiSource, VectorFieldIsRejected) {
  std::string msg = error_of<FormatError>([] { open_field(vti_dir() / "ascii.pvd", "v"); });
  EXPECT_NE(msg.find("ascii_0.vti"), std::string::npos) << msg;
  EXPECT_NE(msg.find("field v has 3 components; a scalar field is expected"), std::string::npos)
      << msg;
}

TEST(VtiSource, MissingFieldListsArrays) {
  std::string msg = error_of<FormatError>([] { open_field(vti_dir() / "ascii_0.vti", "nope"); });
  EXPECT_NE(msg.find("'nope'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("PointData: f, g, v"), std::string::npos) << msg;
  EXPECT_NE(msg.find("CellData: c"), std::string::npos) << msg;
}

TEST(VtiSource, UnsupportedCompressorIsNamed) {
  std::string msg = error_of<FormatError>([] { open_field(vti_dir() / "lz4.vti", "f"); });
  EXPECT_NE(msg.find("lz4.vti"), std::string::npos) << msg;
  EXPECT_NE(msg.find("vtkLZ4DataCompressor"), std::string::npos) << msg;
}

TEST(VtiSource, StepsWithDifferentGridsAreRejected) {
  fs::path dir = tsptest::temp_dir();
  write(dir / "mixed.pvd",
        "<VTKFile type=\"Collection\"><Collection>"
        "<DataSet timestep=\"0\" file=\"" +
            (vti_dir() / "ascii_0.vti").string() +
            "\"/>"
            "<DataSet timestep=\"1\" file=\"" +
            (vti_dir() / "other_dims.vti").string() +
            "\"/>"
            "</Collection></VTKFile>");
  std::string msg = error_of<FormatError>([&] { open_field(dir / "mixed.pvd", "f"); });
  EXPECT_NE(msg.find("other_dims.vti"), std::string::npos) << msg;
  EXPECT_NE(msg.find("4x4x3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("5x4x3"), std::string::npos) << msg;
}

TEST(VtiSource, MissingStepFileIsAnIoError) {
  fs::path dir = tsptest::temp_dir();
  write(dir / "gap.pvd",
        "<VTKFile type=\"Collection\"><Collection>"
        "<DataSet timestep=\"0\" file=\"absent_7.vti\"/></Collection></VTKFile>");
  std::string msg = error_of<IoError>([&] { open_field(dir / "gap.pvd", "f"); });
  EXPECT_NE(msg.find("absent_7.vti"), std::string::npos) << msg;
}

TEST(VtiSource, SeveralPartsPerTimestepAreRejected) {
  fs::path dir = tsptest::temp_dir();
  std::string a = (vti_dir() / "ascii_0.vti").string(), b = (vti_dir() / "ascii_1.vti").string();
  write(dir / "parts.pvd",
        "<VTKFile type=\"Collection\"><Collection>"
        "<DataSet timestep=\"0\" part=\"0\" file=\"" +
            a +
            "\"/>"
            "<DataSet timestep=\"0\" part=\"1\" file=\"" +
            b + "\"/></Collection></VTKFile>");
  std::string msg = error_of<FormatError>([&] { open_field(dir / "parts.pvd", "f"); });
  EXPECT_NE(msg.find("several parts"), std::string::npos) << msg;
}

TEST(VtiSource, TruncatedAppendedDataFailsWithoutCrashing) {
  for (const char* fixture :
       {"appended_raw_0.vti", "zlib_appended_0.vti", "appended_b64_0.vti", "pieces_0.vti"}) {
    std::string bytes = slurp(vti_dir() / fixture);
    for (std::size_t cut : {std::size_t(60), bytes.size() / 2, bytes.size() - bytes.size() / 4}) {
      fs::path p = tsptest::temp_dir() / fixture;
      write(p, bytes.substr(0, bytes.size() - cut));
      EXPECT_THROW(
          {
            auto s = open_field(p, "c");  // c is the last array, so every cut reaches its data
            tsptest::read_step(*s, 0);
          },
          FormatError)
          << fixture << " cut " << cut;
    }
  }
}

TEST(VtiSource, CorruptBase64IsNamed) {
  // Replace one base64 character of the inline data with a character outside the alphabet.
  fs::path p = patched("binary_0.vti", "AAAAAAAAAAAAIA/", "AAAAAAAAAAA#IA/");
  std::string msg = error_of<FormatError>([&] { tsptest::read_step(*open_field(p, "f"), 0); });
  EXPECT_NE(msg.find("base64"), std::string::npos) << msg;
  EXPECT_NE(msg.find("array f"), std::string::npos) << msg;
}

TEST(VtiSource, CorruptZlibBlockIsNamed) {
  std::string bytes = slurp(vti_dir() / "zlib_appended_0.vti");
  std::size_t data = bytes.find('_', bytes.find("<AppendedData")) + 1;
  // Header: 4 words of 4 bytes + one size per block; damage bytes well inside the first block.
  for (std::size_t i = data + 60; i < data + 70; ++i) bytes[i] = char(bytes[i] ^ 0x5a);
  fs::path p = tsptest::temp_dir() / "zlib.vti";
  write(p, bytes);
  std::string msg = error_of<FormatError>([&] { tsptest::read_step(*open_field(p, "f"), 0); });
  EXPECT_NE(msg.find("zlib"), std::string::npos) << msg;
}

TEST(VtiSource, PiecesNotCoveringWholeExtentAreRejected) {
  // Same-length edit keeps every appended offset valid but makes the grid one layer taller.
  fs::path p =
      patched("pieces_0.vti", "WholeExtent=\"0 4 0 3 0 2\"", "WholeExtent=\"0 4 0 3 0 3\"");
  std::string msg = error_of<FormatError>([&] { tsptest::read_step(*open_field(p, "f"), 0); });
  EXPECT_NE(msg.find("do not cover WholeExtent"), std::string::npos) << msg;
}

TEST(VtiSource, UnknownElementTypeIsNamed) {
  fs::path p = patched("ascii_0.vti", "type=\"Float32\" Name=\"f\"", "type=\"Bogus32\" Name=\"f\"");
  std::string msg = error_of<FormatError>([&] { tsptest::read_step(*open_field(p, "f"), 0); });
  EXPECT_NE(msg.find("Bogus32"), std::string::npos) << msg;
}

TEST(VtiSource, WrongValueCountInAsciiIsNamed) {
  // Drop the first value of f (f is the first array, so the first match is its data).
  fs::path p =
      patched("ascii_0.vti", "RangeMax=\"234\">\n        0 1 2", "RangeMax=\"234\">\n        1 2");
  std::string msg = error_of<FormatError>([&] { tsptest::read_step(*open_field(p, "f"), 0); });
  EXPECT_NE(msg.find("holds 59 values, expected 60"), std::string::npos) << msg;
}

TEST(VtiSource, MalformedXmlAndWrongDatasetTypeAreFormatErrors) {
  fs::path dir = tsptest::temp_dir();
  write(dir / "broken.vti", "<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"0 1 0 1 0 1\">");
  std::string msg = error_of<FormatError>([&] { open_field(dir / "broken.vti", "f"); });
  EXPECT_NE(msg.find("not well-formed XML"), std::string::npos) << msg;
  write(dir / "grid.vti", "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid/></VTKFile>");
  msg = error_of<FormatError>([&] { open_field(dir / "grid.vti", "f"); });
  EXPECT_NE(msg.find("\"UnstructuredGrid\", expected \"ImageData\""), std::string::npos) << msg;
}

TEST(VtiSource, BadSeriesJsonIsAFormatError) {
  fs::path dir = tsptest::temp_dir();
  write(dir / "a.vti.series", "{\"file-series-version\": \"1.0\", \"files\": [");
  EXPECT_THROW(open_field(dir / "a.vti.series", "f"), FormatError);
  write(dir / "b.vti.series", "{\"file-series-version\": \"1.0\", \"files\": [{\"name\": 3}]}");
  std::string msg = error_of<FormatError>([&] { open_field(dir / "b.vti.series", "f"); });
  EXPECT_NE(msg.find("files[0]"), std::string::npos) << msg;
  write(dir / "c.vti.series", "{\"file-series-version\": \"2.0\", \"files\": []}");
  msg = error_of<FormatError>([&] { open_field(dir / "c.vti.series", "f"); });
  EXPECT_NE(msg.find("2.0"), std::string::npos) << msg;
}

TEST(VtiSource, PatternOfVtiFilesIsASeriesInPatternOrder) {
  auto s = open_field(vti_dir() / "zlib_appended_%d.vti", "f");
  expect_series(*s, "f", kFixtureDims, "printf pattern");
  auto g = open_field(vti_dir() / "appended_raw_?.vti", "c");
  expect_series(*g, "c", kFixtureCellDims, "glob");
}

}  // namespace
}  // namespace tsp
