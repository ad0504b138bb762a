// The session options' table (src/cli/session_options.h): every row is complete and unique, and
// every command that takes a row shows its one help (render, bench and play alike), so an option
// means the same in each.
#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <string>

#include "cli/session_options.h"
#include "support/paths.h"

namespace {

TEST(SessionOptions, RowsAreUniqueAndComplete) {
  std::set<std::string_view> names;
  for (const tspcli::SessionOptionSpec& s : tspcli::session_options()) {
    EXPECT_TRUE(names.insert(s.name).second) << s.name << " twice";
    EXPECT_EQ(s.name.rfind("--", 0), 0u) << s.name;
    EXPECT_FALSE(s.group.empty()) << s.name;
    EXPECT_GT(s.help.size(), 10u) << s.name;
  }
  EXPECT_EQ(tspcli::lod_word("on"), "auto");
  EXPECT_EQ(tspcli::lod_word("off"), "off");
  EXPECT_EQ(tspcli::lod_word("2"), "2");
}

// The --help line of option `name` in `help` ("" when the command has no such option).
std::string help_line(const std::string& help, std::string_view name) {
  std::istringstream in(help);
  std::string line;
  const std::string key = "  " + std::string(name) + " ";
  std::string found;
  while (std::getline(in, line)) {
    if (!found.empty()) {  // CLI11 puts the help on the next line after a long type column
      const std::size_t text = line.find_first_not_of(' ');
      if (text == std::string::npos || text < 4) break;
      found += " " + line.substr(text);
    } else if (line.rfind(key, 0) == 0) {
      found = line;
    }
  }
  return found;
}

TEST(SessionOptions, EveryCommandShowsEachRowsOneHelp) {
  for (const char* command : {"render", "bench", "play"}) {
    const auto r = tsptest::run_tspplay(std::string(command) + " --help");
    ASSERT_EQ(r.exit_code, 0) << command << ": " << r.err;
    int shared = 0;
    for (const tspcli::SessionOptionSpec& s : tspcli::session_options()) {
      const std::string line = help_line(r.out, s.name);
      if (line.empty()) continue;
      ++shared;
      EXPECT_NE(line.find(std::string(s.help)), std::string::npos)
          << command << " " << s.name << " has its own help:\n" << line;
    }
    EXPECT_GE(shared, 4) << command;
  }
}

}  // namespace
