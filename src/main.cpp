// tspplay: play time-varying volume data with TSP trees. main only parses and dispatches.
#include <cstdio>
#include <exception>

#include "cli/commands.h"
#include "tsp/core/error.h"

int main(int argc, char** argv) {
  CLI::App app{"tspplay " TSPPLAY_VERSION " - play time-varying volume data with TSP trees"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "tspplay " TSPPLAY_VERSION);
  tspcli::add_all_commands(app);
  try {
    app.parse(argc, argv);
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
