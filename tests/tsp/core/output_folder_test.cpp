// The one output mechanism at library level: TempOutput's refusals (guarded inputs, non-regular
// files, commits after an interruption), links written through, and OutputFolder's whole-folder
// replacement (the set dropped, other files kept by inode, refusals, stale temporary folders).
#include "tsp/core/output_folder.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/paths.h"
#include "support/reader_formula.h"
#include "tsp/core/error.h"
#include "tsp/core/interrupt.h"
#include "tsp/core/temp_output.h"

namespace {

namespace fs = std::filesystem;
using namespace tsp;
using tsptest::error_of;

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

ino_t inode(const fs::path& p) {
  struct stat st {};
  return ::stat(p.c_str(), &st) == 0 ? st.st_ino : 0;
}

// The entries of dir whose name starts with '.'.
int hidden_entries(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string()[0] == '.';
  return n;
}

bool frame_set(const std::string& name) { return name.rfind("f", 0) == 0; }  // f0, f1, ...

TEST(TempOutput, GuardedInputsAndNonRegularFilesAreRefused) {
  const fs::path dir = tsptest::temp_dir();
  write(dir / "in.txt", "input");
  fs::create_symlink(dir / "in.txt", dir / "link.txt");
  {
    const InputGuard guard({(dir / "in.txt").string()});
    for (const char* name : {"in.txt", "link.txt"}) {
      const std::string m =
          error_of<UsageError>([&] { TempOutput out((dir / name).string()); });
      EXPECT_NE(m.find("the output is the input file " + (dir / "in.txt").string()),
                std::string::npos) << m;
    }
    EXPECT_NO_THROW(TempOutput((dir / "other.txt").string()));  // a new name is no input
  }
  write_file_atomically((dir / "in.txt").string(), "output");  // unguarded again
  EXPECT_EQ(tsptest::read_file(dir / "in.txt"), "output");
  ASSERT_EQ(::mkfifo((dir / "p").c_str(), 0600), 0);
  const std::string m = error_of<IoError>([&] { write_file_atomically((dir / "p").string(), "x"); });
  EXPECT_NE(m.find("p: is a FIFO, not a regular file"), std::string::npos) << m;
  EXPECT_TRUE(fs::is_fifo(dir / "p"));
  EXPECT_EQ(hidden_entries(dir), 0);
}

TEST(TempOutput, ALinkIsWrittenThroughAndKept) {
  const fs::path dir = tsptest::temp_dir();
  fs::create_directory(dir / "target");
  write(dir / "target" / "f.json", "old");
  fs::create_symlink(dir / "target" / "f.json", dir / "f.json");
  write_file_atomically((dir / "f.json").string(), "new");
  EXPECT_TRUE(fs::is_symlink(dir / "f.json"));
  EXPECT_EQ(tsptest::read_file(dir / "target" / "f.json"), "new");
}

TEST(TempOutput, UnderReplaceALinkIsReplacedAndItsTargetUntouched) {
  // A cache entry: another user may plant a link at its name, to a file of the victim's or to
  // a device; the link itself goes, whatever it points at.
  const fs::path dir = tsptest::temp_dir();
  write(dir / "victim.txt", "precious");
  fs::create_symlink(dir / "victim.txt", dir / "entry.json");
  fs::create_symlink("/dev/null", dir / "dev.json");
  write_file_atomically((dir / "entry.json").string(), "cache", OutputLinks::replace);
  write_file_atomically((dir / "dev.json").string(), "cache", OutputLinks::replace);
  EXPECT_EQ(tsptest::read_file(dir / "victim.txt"), "precious");
  for (const char* name : {"entry.json", "dev.json"}) {
    EXPECT_FALSE(fs::is_symlink(dir / name)) << name;
    EXPECT_EQ(tsptest::read_file(dir / name), "cache") << name;
  }
  EXPECT_EQ(hidden_entries(dir), 0);
}

TEST(TempOutput, NothingIsCommittedAfterAnInterruption) {
  const fs::path dir = tsptest::temp_dir();
  write(dir / "out.txt", "old");
  {
    TempOutput out((dir / "out.txt").string());
    write(out.tmp(), "new");
    detail::simulate_interrupt(SIGINT);
    const std::string m = error_of<Interrupted>([&] { out.commit(); });
    detail::clear_interrupt();
    EXPECT_NE(m.find("interrupted by SIGINT"), std::string::npos) << m;
  }
  EXPECT_EQ(tsptest::read_file(dir / "out.txt"), "old");
  EXPECT_EQ(hidden_entries(dir), 0);
}

TEST(OutputFolder, TheSetIsReplacedAsAWholeAndOtherFilesKept) {
  const fs::path dir = tsptest::temp_dir(), out = dir / "frames";
  {
    OutputFolder f(out.string(), frame_set);  // a new folder is empty until the commit
    write(fs::path(f.tmp()) / "f0", "a0");
    EXPECT_TRUE(fs::is_empty(out));
  }
  EXPECT_FALSE(fs::exists(out));  // and gone again without one
  {
    OutputFolder f(out.string(), frame_set);
    write(fs::path(f.tmp()) / "f0", "a0");
    write(fs::path(f.tmp()) / "f1", "a1");
    f.commit();
  }
  write(out / "notes", "mine");
  const ino_t notes = inode(out / "notes");
  {
    OutputFolder f(out.string(), frame_set);
    write(fs::path(f.tmp()) / "f0", "b0");
  }  // not committed: the old set stays
  EXPECT_EQ(tsptest::read_file(out / "f1"), "a1");
  EXPECT_EQ(hidden_entries(dir), 0);
  {
    OutputFolder f(out.string(), frame_set);
    write(fs::path(f.tmp()) / "f0", "b0");
    f.commit();
  }
  EXPECT_EQ(tsptest::read_file(out / "f0"), "b0");
  EXPECT_FALSE(fs::exists(out / "f1"));  // no old frame beside the new ones
  EXPECT_EQ(tsptest::read_file(out / "notes"), "mine");
  EXPECT_EQ(inode(out / "notes"), notes);  // the same file, not a copy
  EXPECT_EQ(hidden_entries(dir), 0);
  EXPECT_EQ(hidden_entries(out), 0);
}

TEST(OutputFolder, InputsInTheSetSubfoldersAndTheWorkingFolderAreRefused) {
  const fs::path dir = tsptest::temp_dir(), out = dir / "frames";
  fs::create_directory(out);
  write(out / "f0", "input");
  write(out / "keep", "not in the set");
  {
    const InputGuard guard({(out / "f0").string(), (out / "keep").string()});
    const std::string m = error_of<UsageError>([&] { OutputFolder f(out.string(), frame_set); });
    EXPECT_NE(m.find("f0 is the input file"), std::string::npos) << m;
  }
  {
    const InputGuard guard({(out / "keep").string()});  // carried over, so allowed
    OutputFolder f(out.string(), frame_set);
    f.commit();
    EXPECT_EQ(tsptest::read_file(out / "keep"), "not in the set");
  }
  fs::create_directory(out / "sub");
  std::string m = error_of<IoError>([&] { OutputFolder f(out.string(), frame_set); });
  EXPECT_NE(m.find("holds sub (a folder)"), std::string::npos) << m;
  fs::remove(out / "sub");
  write(dir / "file", "x");
  m = error_of<IoError>([&] { OutputFolder f((dir / "file").string(), frame_set); });
  EXPECT_NE(m.find("is not a folder"), std::string::npos) << m;
  const fs::path here = fs::current_path();
  fs::current_path(out);
  m = error_of<UsageError>([&] { OutputFolder f(".", frame_set); });
  fs::current_path(here);
  EXPECT_NE(m.find("the current folder is inside it"), std::string::npos) << m;
  EXPECT_EQ(hidden_entries(dir), 0);
}

TEST(OutputFolder, StaleTemporaryFoldersAreSweptLiveOnesKept) {
  const fs::path dir = tsptest::temp_dir(), out = dir / "frames";
  // A writer killed outright: its folder and unlocked marker remain; an old set whose removal
  // was cut short has no marker.
  fs::create_directories(dir / ".frames.tmp-AAAAAA");
  write(dir / ".frames.tmp-AAAAAA" / ".tspplay-writing", "");
  fs::create_directories(dir / ".frames.tmp-BBBBBB");
  write(dir / ".frames.tmp-BBBBBB" / "f0", "old");
  OutputFolder live(out.string(), frame_set);
  EXPECT_FALSE(fs::exists(dir / ".frames.tmp-AAAAAA"));
  EXPECT_FALSE(fs::exists(dir / ".frames.tmp-BBBBBB"));
  EXPECT_EQ(remove_stale_temporary_folders(out.string()), 0);  // live's marker is locked
  EXPECT_TRUE(fs::is_directory(live.tmp()));
}

// A new output's free name: the name itself while nothing is there, then STEM-2.EXT, STEM-3.EXT
// (a dangling link counts as taken: the player's S and Record never replace an earlier file).
TEST(UnusedPath, TakesTheNameOrTheFirstFreeNumberedOne) {
  const fs::path dir = tsptest::temp_dir();
  const std::string movie = (dir / "tspplay_movie.mp4").string();
  EXPECT_EQ(tsp::unused_path(movie), movie);
  std::ofstream(movie) << "x";
  EXPECT_EQ(tsp::unused_path(movie), (dir / "tspplay_movie-2.mp4").string());
  fs::create_symlink(dir / "gone", dir / "tspplay_movie-2.mp4");
  EXPECT_EQ(tsp::unused_path(movie), (dir / "tspplay_movie-3.mp4").string());
}

}  // namespace
