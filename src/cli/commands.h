// src/cli: the subcommands; may include every other folder.
// Subcommands register themselves here; main() only parses and dispatches.
#pragma once
#include <CLI/CLI.hpp>
#include <functional>

namespace tspcli {

/// Adds one subcommand to the app; its callback runs the command.
using AddCommand = std::function<void(CLI::App&)>;

/// Registers a subcommand at static-initialisation time; `order` sorts the help listing.
struct CommandRegistrar {
  CommandRegistrar(int order, AddCommand add);
};

/// Adds every registered subcommand to app, in order.
void add_all_commands(CLI::App& app);

}  // namespace tspcli
