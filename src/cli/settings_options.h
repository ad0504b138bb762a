// The render settings table (render/settings_table.h) as CLI11 options: one option per row, in
// its group, with the command's own default in the help; parsed and validated by the table.
#pragma once
#include <CLI/CLI.hpp>
#include <map>
#include <string>
#include <vector>

#include "render/render_settings.h"

namespace tspcli {

/// The settings options of one subcommand. Make it with the command's defaults, add_to() the
/// subcommand, then apply() in its callback.
class SettingsOptions {
 public:
  /// defaults: what the command draws with when an option is not given (shown in --help).
  explicit SettingsOptions(const tspgl::RenderSettings& defaults = {}) : defaults_(defaults) {}
  /// Adds --NAME for every row of the table to c, under the row's group heading. Never throws.
  void add_to(CLI::App* c);
  /// The defaults with every given option parsed in, then validated (tspgl::validate). Throws
  /// tsp::UsageError naming the option, the text and what it accepts.
  tspgl::RenderSettings apply() const;
  /// The options given on the command line ("--spacing", ...), in table order.
  std::vector<std::string> given() const;

 private:
  tspgl::RenderSettings defaults_;
  std::map<std::string, std::string> texts_;  // by name; filled by CLI11
  std::vector<std::pair<std::string, CLI::Option*>> options_;
};

/// Adds a switch `--NAME [on|off]` to c storing "on" or "off" in value (given alone it means
/// on; its default is value's initial text, shown in the help). Never throws.
CLI::Option* on_off_option(CLI::App* c, const std::string& name, std::string& value,
                           const std::string& help);

/// Puts each named option of c ("--size", by its long name) under its group's heading in
/// --help; asserts every name is an option of c. Never throws.
void set_groups(CLI::App* c,
                const std::vector<std::pair<std::string, std::vector<std::string>>>& groups);

}  // namespace tspcli
