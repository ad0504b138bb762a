// The unstructured readers (.vtu in every VTK encoding, .pvd, .vtu.series, .vtm.series, VTKHDF)
// against the fixtures' formula (tests/data/make_mesh_fixtures.py), and their errors on bad input.
#include "tsp/source/open_mesh_source.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/paths.h"
#include "tsp/core/error.h"

namespace tsp {
namespace {

namespace fs = std::filesystem;

fs::path dir() { return tsptest::test_data_dir() / "vtu"; }

constexpr int kCells = 6;
constexpr int kPoints = 4 + 8 + 8 + 6 + 5 + 8;
const CellType kTypes[kCells] = {CellType::tetra,  CellType::voxel,   CellType::hexahedron,
                                 CellType::wedge,  CellType::pyramid, CellType::polyhedron};

// Every point value is f = x + 10y + 100z + 1000t, exact in float.
void expect_formula(const Mesh& m, int t, const std::string& tag) {
  SCOPED_TRACE(tag);
  ASSERT_EQ(m.point_count(), kPoints);
  ASSERT_EQ(m.cell_count(), kCells);
  ASSERT_FALSE(m.cell_values);
  for (int c = 0; c < kCells; ++c) EXPECT_EQ(m.types[std::size_t(c)], kTypes[c]) << c;
  for (std::int64_t p = 0; p < m.point_count(); ++p) {
    const double* x = m.points.data() + 3 * p;
    EXPECT_EQ(m.values[std::size_t(p)], float(x[0] + 10 * x[1] + 100 * x[2] + 1000 * t)) << p;
  }
  // The polyhedron's face stream: 6 quads of its own 8 points.
  ASSERT_EQ(m.face_start.size(), std::size_t(kCells));
  for (int c = 0; c + 1 < kCells; ++c) EXPECT_EQ(m.face_start[std::size_t(c)], -1);
  EXPECT_EQ(m.faces[std::size_t(m.face_start[kCells - 1])], 6);
}

TEST(MeshSource, VtuInEveryEncodingReadsTheFormula) {
  for (const char* v : {"ascii", "binary", "appended", "base64", "zlib64", "zlib_binary"}) {
    auto s = open_mesh_source((dir() / (std::string(v) + "_1.vtu")).string(), "f");
    ASSERT_EQ(s->steps(), 1);
    expect_formula(s->read_step(0), 1, v);
  }
}

TEST(MeshSource, CollectionsSortByTimeAndKeepTheTimes) {
  for (const char* list : {"mixed.pvd", "mixed.vtu.series", "case.vtm.series"}) {
    auto s = open_mesh_source((dir() / list).string(), "");  // f is the active scalars
    ASSERT_EQ(s->steps(), 3) << list;
    EXPECT_EQ(s->times(), (std::vector<double>{0.0, 0.25, 0.5})) << list;
    // Time 0 is step 1 of the fixtures, 0.25 step 2, 0.5 step 0.
    const int fixture_step[3] = {1, 2, 0};
    for (int t = 0; t < 3; ++t) {
      const Mesh m = s->read_step(t);
      expect_formula(m, fixture_step[t], list);
      EXPECT_EQ(s->bounds(t), m.bounds()) << list;  // the points-only read agrees
    }
  }
}

TEST(MeshSource, VectorComponentsMagnitudeAndCellData) {
  const std::string f = (dir() / "zlib64_0.vtu").string();
  Mesh x = open_mesh_source(f, "v:x")->read_step(0);
  Mesh z = open_mesh_source(f, "v:z")->read_step(0);
  Mesh mag = open_mesh_source(f, "v:mag")->read_step(0);
  for (std::int64_t p = 0; p < x.point_count(); ++p) {
    const double* q = x.points.data() + 3 * p;
    EXPECT_EQ(x.values[std::size_t(p)], float(q[0]));
    EXPECT_EQ(z.values[std::size_t(p)], float(3 * q[2]));
    EXPECT_FLOAT_EQ(mag.values[std::size_t(p)],
                    float(std::sqrt(q[0] * q[0] + 4 * q[1] * q[1] + 9 * q[2] * q[2])));
  }
  Mesh c = open_mesh_source(f, "c")->read_step(0);
  ASSERT_TRUE(c.cell_values);
  for (int k = 0; k < kCells; ++k) EXPECT_EQ(c.values[std::size_t(k)], float(7 * k));
  EXPECT_THROW(open_mesh_source(f, "v"), FormatError);    // a vector needs :mag or :x|y|z
  EXPECT_THROW(open_mesh_source(f, "v:w"), UsageError);
  EXPECT_THROW(open_mesh_source(f, "nope"), FormatError);
}

TEST(MeshSource, VtkhdfPatternMatchesTheVtu) {
  auto s = open_mesh_source((dir() / "mesh_%d.hdf").string(), "f");
  ASSERT_EQ(s->steps(), 3);
  for (int t = 0; t < 3; ++t) {
    Mesh m = s->read_step(t);
    ASSERT_EQ(m.cell_count(), kCells - 1);  // written without the polyhedron
    for (std::int64_t p = 0; p < m.point_count(); ++p) {
      const double* x = m.points.data() + 3 * p;
      EXPECT_EQ(m.values[std::size_t(p)], float(x[0] + 10 * x[1] + 100 * x[2] + 1000 * t));
    }
  }
  Mesh c = open_mesh_source((dir() / "mesh_0.hdf").string(), "c")->read_step(0);
  EXPECT_TRUE(c.cell_values);
  EXPECT_TRUE(is_mesh_input((dir() / "mesh_1.hdf").string()));
  EXPECT_FALSE(is_mesh_input((tsptest::test_data_dir() / "h5" / "vtkhdf_static.hdf").string()));
}

TEST(MeshSource, TransientVtkhdfReadsEachStepsMeshAndData) {
  // One file, a Steps group: step t's mesh is the fixture moved by +t along x, with its own
  // rows of Points/Offsets/Connectivity/Types and point and cell data.
  auto s = open_mesh_source((dir() / "transient.hdf").string(), "f");
  ASSERT_EQ(s->steps(), 3);
  EXPECT_EQ(s->times(), (std::vector<double>{0.0, 0.25, 0.5}));  // Steps/Values, in file order
  for (int t = 0; t < 3; ++t) {
    Mesh m = s->read_step(t);
    ASSERT_EQ(m.cell_count(), kCells - 1);
    EXPECT_DOUBLE_EQ(m.bounds().lo[0], t);
    for (std::int64_t p = 0; p < m.point_count(); ++p) {
      const double* x = m.points.data() + 3 * p;
      EXPECT_EQ(m.values[std::size_t(p)], float(x[0] + 10 * x[1] + 100 * x[2] + 1000 * t));
    }
  }
  Mesh c = open_mesh_source((dir() / "transient.hdf").string(), "c")->read_step(2);
  ASSERT_TRUE(c.cell_values);
  for (int k = 0; k < kCells - 1; ++k) EXPECT_EQ(c.values[std::size_t(k)], float(7 * k + 2));
}

// Hostile inputs: a copy of the ascii fixture with one thing broken.
std::string error_for(const std::string& from, const std::string& to) {
  std::ifstream in(dir() / "ascii_0.vtu");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  // In the test's own directory: ctest runs the tests of this file in parallel.
  const fs::path p = tsptest::temp_dir() / "tspplay_bad_mesh.vtu";
  std::ofstream(p) << text;
  try {
    open_mesh_source(p.string(), "f")->read_step(0);
  } catch (const FormatError& e) {
    fs::remove(p);
    return e.what();
  }
  fs::remove(p);
  return "no error";
}

TEST(MeshSource, MalformedVtuNamesTheFileAndTheArray) {
  const std::string name = "tspplay_bad_mesh.vtu";
  std::string e = error_for("NumberOfCells=\"6\"", "NumberOfCells=\"60000000000\"");
  EXPECT_NE(e.find(name), std::string::npos) << e;
  EXPECT_NE(e.find("offsets"), std::string::npos) << e;
  e = error_for("NumberOfPoints=\"39\"", "NumberOfPoints=\"-3\"");
  EXPECT_NE(e.find("NumberOfPoints"), std::string::npos) << e;
  // A connectivity entry naming a point that does not exist.
  e = error_for("Name=\"connectivity\" format=\"ascii\" RangeMin=\"0\" RangeMax=\"38\">\n          0",
                "Name=\"connectivity\" format=\"ascii\" RangeMin=\"0\" RangeMax=\"38\">\n          99");
  EXPECT_NE(e.find("connectivity"), std::string::npos) << e;
  EXPECT_NE(e.find("99"), std::string::npos) << e;
  // A cell type out of range.
  e = error_for("Name=\"types\" format=\"ascii\" RangeMin=\"10\" RangeMax=\"42\">\n          10",
                "Name=\"types\" format=\"ascii\" RangeMin=\"10\" RangeMax=\"42\">\n          77");
  EXPECT_NE(e.find("type 77"), std::string::npos) << e;
}

TEST(MeshSource, HugeCountsAreRefusedBeforeAllocating) {
  // 10^11 points claimed in a few hundred characters: refused before 2.4 TB are allocated.
  const std::string e = error_for("NumberOfPoints=\"39\"", "NumberOfPoints=\"100000000000\"");
  EXPECT_NE(e.find("Points"), std::string::npos) << e;
  EXPECT_NE(e.find("holds only"), std::string::npos) << e;
}

TEST(MeshSource, LyingZlibHeaderIsNamedNotAllocated) {
  // The Points header claims blocks of 4 GiB: refused before anything that size is allocated.
  try {
    open_mesh_source((dir() / "hostile_zlib_lie.vtu").string(), "f")->read_step(0);
    FAIL() << "no error";
  } catch (const FormatError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("hostile_zlib_lie.vtu"), std::string::npos) << m;
    EXPECT_NE(m.find("zlib"), std::string::npos) << m;
  }
}

TEST(MeshSource, MalformedVtkhdfNamesTheFileAndTheDataset) {
  const std::pair<const char*, const char*> cases[] = {
      {"hostile_vtkhdf_connectivity.hdf", "Connectivity"},
      {"hostile_vtkhdf_type.hdf", "type 77"},
      {"hostile_vtkhdf_offsets.hdf", "Offsets"}};
  for (const auto& [file, what] : cases) {
    try {
      open_mesh_source((dir() / file).string(), "f")->read_step(0);
      ADD_FAILURE() << file << ": no error";
    } catch (const FormatError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(file), std::string::npos) << m;
      EXPECT_NE(m.find(what), std::string::npos) << m;
    }
  }
}

}  // namespace
}  // namespace tsp
