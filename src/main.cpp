// tspplay: play time-varying volume data with TSP trees. main only parses and dispatches.
#include <cstdio>
#include <exception>
#include <string>

#include "cli/commands.h"
#include "tsp/core/error.h"
#include "tsp/core/interrupt.h"

int main(int argc, char** argv) {
  CLI::App app{"tspplay " TSPPLAY_VERSION " - play time-varying volume data with TSP trees"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "tspplay " TSPPLAY_VERSION);
  tspcli::add_all_commands(app);
  // An unknown first word is a mistyped subcommand: say which exist (CLI11 alone says only that
  // one is required).
  if (argc > 1 && argv[1][0] != '-') {
    std::string names;
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
      names += (names.empty() ? "" : ", ") + sub->get_name();
      known |= sub->get_name() == argv[1];
    }
    if (!known) {
      std::fprintf(stderr, "tspplay: usage error: unknown subcommand '%s'; the subcommands are %s "
                   "(tspplay --help)\n", argv[1], names.c_str());
      return 2;
    }
  }
  // SIGINT/SIGTERM end every command the same way: a message, temporaries removed, exit 1, old
  // outputs intact (tsp/core/interrupt.h).
  const tsp::InterruptScope interrupts;
  try {
    app.parse(argc, argv);
    tsp::throw_if_interrupted();  // a command with nothing left to stop still says so
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every other parse error is a usage error (exit 2).
    int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const tsp::UsageError& e) {
    std::fprintf(stderr, "tspplay: usage error: %s\n", e.what());
    return 2;
  } catch (const tsp::Error& e) {
    std::fprintf(stderr, "tspplay: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tspplay: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
