// The session options' table (src/cli/session_options.h): every row is complete and unique, and
// every command that takes a row shows its one help (render, bench and play alike), so an option
// means the same in each.
#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <string>

#include "cli/session_options.h"
#include "jobs/render_job.h"
#include "support/paths.h"

namespace {

TEST(SessionOptions, RowsAreUniqueAndComplete) {
  std::set<std::string_view> names;
  for (const tspcli::SessionOptionSpec& s : tspcli::session_options()) {
    EXPECT_TRUE(names.insert(s.name).second) << s.name << " twice";
    EXPECT_EQ(s.name.rfind("--", 0), 0u) << s.name;
    EXPECT_FALSE(s.group.empty()) << s.name;
    EXPECT_GT(s.help.size(), 10u) << s.name;
    int takers = 0;
    for (const tspcli::SessionDefault& d : s.defaults) {
      takers += d.taken;
      EXPECT_TRUE(d.taken || (d.value.empty() && d.shown.empty())) << s.name;
    }
    EXPECT_GE(takers, 2) << s.name << ": a row of one command is that command's own option";
    // A default stated in the help is never part of the help itself (it differs per command).
    EXPECT_EQ(s.help.find("(default"), std::string_view::npos) << s.name;
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

// Each command starts from its own defaults, stated in the table, as the library's constants.
TEST(SessionOptions, EachCommandsDefaultsComeFromTheTable) {
  using tspcli::SessionCommand;
  const tspcli::SessionArgs render = tspcli::session_defaults(SessionCommand::render);
  const tspcli::SessionArgs play = tspcli::session_defaults(SessionCommand::play);
  const tspcli::SessionArgs bench = tspcli::session_defaults(SessionCommand::bench);
  EXPECT_EQ(render.size, "640x480");
  EXPECT_EQ(play.size, "960x720");
  EXPECT_EQ(bench.size, "640x480");
  EXPECT_EQ(render.tf, "preset:auto");
  EXPECT_EQ(bench.tf, "preset:sparse");
  EXPECT_EQ(render.probe_surface, "off");
  EXPECT_EQ(play.probe_surface, "on");
  EXPECT_EQ(render.lod, "");  // off, or auto with --target-fps
  EXPECT_EQ(play.lod, "auto");
  EXPECT_EQ(render.quality, 0);
  EXPECT_EQ(play.quality, 1);
  EXPECT_EQ(play.target_fps, 30);
  EXPECT_EQ(render.gpu, -1);
  EXPECT_EQ(render.probe_op, "intersect");
  EXPECT_TRUE(render.probes.empty());
  for (const tspcli::SessionArgs* a : {&render, &play}) {
    EXPECT_EQ(a->texture_budget_mb, double(tspgl::kDefaultTextureBudget >> 20));
    EXPECT_EQ(a->ram_budget_mb, double(tspgl::kDefaultBrickBudget >> 20));
  }
  // The help states each command's default: "(default 960x720)" in play's.
  EXPECT_NE(tspcli::session_help(tspcli::session_option("--size"), SessionCommand::play)
                .find("(default 960x720)"),
            std::string::npos);
}

// The help line of a row without its "(default …)": what the option means.
std::string meaning(std::string line) {
  const std::size_t d = line.rfind(" (default ");
  return d == std::string::npos ? line : line.substr(0, d);
}

// render --help and play --help show every option both take with the same help, and each
// with exactly the table's text for that command (its default included).
TEST(SessionOptions, RenderAndPlayHelpAgreeOnEverySharedOption) {
  using tspcli::SessionCommand;
  const auto render = tsptest::run_tspplay("render --help");
  const auto play = tsptest::run_tspplay("play --help");
  ASSERT_EQ(render.exit_code, 0) << render.err;
  ASSERT_EQ(play.exit_code, 0) << play.err;
  int shared = 0;
  for (const tspcli::SessionOptionSpec& s : tspcli::session_options()) {
    const std::string r = help_line(render.out, s.name), p = help_line(play.out, s.name);
    EXPECT_EQ(r.empty(), !s.in(SessionCommand::render).taken) << s.name;
    EXPECT_EQ(p.empty(), !s.in(SessionCommand::play).taken) << s.name;
    if (!r.empty())
      EXPECT_NE(r.find(tspcli::session_help(s, SessionCommand::render)), std::string::npos)
          << s.name << ":\n" << r;
    if (!p.empty())
      EXPECT_NE(p.find(tspcli::session_help(s, SessionCommand::play)), std::string::npos)
          << s.name << ":\n" << p;
    if (r.empty() || p.empty()) continue;
    ++shared;
    // The same words after the option's name and type column.
    const auto text = [&](const std::string& line) {
      return meaning(line.substr(line.find(std::string(s.help.substr(0, 12)))));
    };
    EXPECT_EQ(text(r), text(p)) << s.name;
  }
  EXPECT_GE(shared, 18);
}

// A row's accepted words are checked alike in every command that takes it.
TEST(SessionOptions, ARowsWordsAreCheckedAlikeEverywhere) {
  const auto r = tsptest::run_tspplay("render nofile.tsp -o out --probe-op xor");
  const auto p = tsptest::run_tspplay("play nofile.tsp --probe-op xor");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(p.exit_code, 0) << p.err;
  const std::string said = "--probe-op: xor not in {intersect,union,subtract}";
  EXPECT_NE(r.err.find(said), std::string::npos) << r.err;
  EXPECT_NE(p.err.find(said), std::string::npos) << p.err;
}

// One registration fills SessionArgs' fields by type; bench's several --tf replace its default.
TEST(SessionOptions, OneRegistrationParsesIntoTheStruct) {
  using tspcli::SessionCommand;
  CLI::App app("render");
  tspcli::SessionArgs a = tspcli::session_defaults(SessionCommand::render);
  tspcli::add_session_options(&app, SessionCommand::render, a);
  app.parse("--size 10x20 --probe plane:0,0,1,5 --probe sphere:1,2,3,4 --gpu 2 --quality 1.5 "
            "--lod on --probe-surface on",
            false);
  EXPECT_EQ(a.size, "10x20");
  EXPECT_EQ(a.probes, (std::vector<std::string>{"plane:0,0,1,5", "sphere:1,2,3,4"}));
  EXPECT_EQ(a.gpu, 2);
  EXPECT_EQ(a.quality, 1.5);
  EXPECT_EQ(tspcli::lod_word(a.lod), "auto");
  EXPECT_EQ(a.probe_surface, "on");
  EXPECT_EQ(a.view, "30,20");  // not given: render's default
  EXPECT_EQ(app.get_option_no_throw("--speed"), nullptr);  // play's own, not a session option

  CLI::App bench("bench");
  tspcli::SessionArgs b = tspcli::session_defaults(SessionCommand::bench);
  std::vector<std::string> tfs{b.tf};
  tspcli::add_session_options(&bench, SessionCommand::bench, b, {"--tf"});
  tspcli::add_session_option(&bench, SessionCommand::bench, "--tf", tfs);
  EXPECT_EQ(bench.get_option_no_throw("--probe"), nullptr);  // render and play's
  bench.parse("--tf preset:filled --tf a.json", false);
  EXPECT_EQ(tfs, (std::vector<std::string>{"preset:filled", "a.json"}));
}

}  // namespace
