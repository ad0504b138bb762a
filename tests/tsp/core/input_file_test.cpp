// The input gate: regular files read exactly, anything else refused at open without blocking,
// a file over the limit refused before it is read.
#include "tsp/core/input_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>

#include "support/paths.h"
#include "tsp/core/error.h"

namespace {

namespace fs = std::filesystem;

std::string error_of(const std::string& path, std::int64_t limit = tsp::kMaxTextInputBytes) {
  try {
    tsp::read_input_file(path, "test input", limit);
  } catch (const tsp::IoError& e) {
    return e.what();
  }
  return "";
}

TEST(InputFile, ReadsARegularFileExactly) {
  const fs::path p = tsptest::temp_dir() / "a.txt";
  const std::string text("line one\n\0binary\xff", 18);
  std::ofstream(p, std::ios::binary) << text;
  EXPECT_EQ(tsp::read_input_file(p.string(), "test input"), text);
  tsp::InputFile f(p.string(), "test input");
  EXPECT_EQ(f.size(), 18);
  char buf[64];
  EXPECT_EQ(f.read(buf, 5), 5u);
  EXPECT_EQ(f.read(buf, sizeof buf), 13u);
  EXPECT_EQ(f.read(buf, sizeof buf), 0u);
}

TEST(InputFile, RefusesFifosDevicesDirectoriesAndMissingFilesAtOnce) {
  const fs::path dir = tsptest::temp_dir(), fifo = dir / "pipe";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  // (Opening the FIFO without O_NONBLOCK would wait here forever for a writer.)
  EXPECT_EQ(error_of(fifo.string()),
            fifo.string() + ": test input is not a regular file (a FIFO, socket or device)");
  EXPECT_EQ(error_of("/dev/zero"),
            "/dev/zero: test input is not a regular file (a FIFO, socket or device)");
  EXPECT_EQ(error_of(dir.string()), dir.string() + ": test input is a directory, expected a file");
  EXPECT_EQ(error_of((dir / "none").string()), (dir / "none").string() + ": test input does not exist");
}

TEST(InputFile, RefusesAFileOverTheLimitBeforeReadingIt) {
  const fs::path p = tsptest::temp_dir() / "big.txt";
  std::ofstream(p) << std::string(100, 'x');
  EXPECT_EQ(error_of(p.string(), 99),
            p.string() + ": test input holds 100 bytes, more than the 99 bytes accepted");
  EXPECT_EQ(error_of(p.string(), 100), "");
}

}  // namespace
