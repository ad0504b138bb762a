// Dispatch of tsp::open_source on the input's form (the readers themselves have own tests).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/paths.h"
#include "tsp/core/error.h"
#include "tsp/source/open_source.h"
#include "tsp/source/volume_source.h"

namespace tsp {
namespace {

namespace fs = std::filesystem;

TEST(OpenSource, PicksTheReaderByForm) {
  fs::path data = tsptest::test_data_dir();
  SourceOptions o;
  EXPECT_NE(open_source((data / "h5" / "grid4d.h5").string(), o)->describe().find("dataset /f"),
            std::string::npos);
  EXPECT_NE(open_source((data / "h5" / "vtkhdf_static.hdf").string(), o)->describe().find("VTKHDF"),
            std::string::npos);
  EXPECT_EQ(open_source((data / "vti" / "ascii.pvd").string(), o)->steps(), 3);
  EXPECT_EQ(open_source((data / "vti" / "ascii.vti.series").string(), o)->steps(), 3);
  EXPECT_EQ(open_source((data / "vti" / "ascii_1.vti").string(), o)->steps(), 1);
}

TEST(OpenSource, BadRequestsGiveTypedErrors) {
  fs::path dir = tsptest::temp_dir();
  SourceOptions o;
  EXPECT_THROW(open_source("", o), UsageError);
  EXPECT_THROW(open_source((dir / "missing.h5").string(), o), IoError);
  EXPECT_THROW(open_source((dir / "missing.pvd").string(), o), IoError);
  EXPECT_THROW(open_source(dir.string(), o), IoError);
  EXPECT_THROW(open_source((dir / "step_%d.h5").string(), o), UsageError);
  std::ofstream(dir / "notes.txt") << "hello\n";
  try {
    open_source((dir / "notes.txt").string(), o);
    ADD_FAILURE() << "no exception";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("notes.txt: unrecognised input"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tsp
