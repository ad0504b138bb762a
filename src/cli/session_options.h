// The session options (input, view, LOD, probes, TF, budgets, surface, quality): what a run of
// frames is drawn from and with besides the render settings' knobs. As the settings table does
// for the knobs (settings_options.h), this table gives each option one name, one meaning and one
// help, in its group, in every command that takes it (render, play, bench); a command adds the
// rows it takes with its own default, which the help states.
#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace tspcli {

/// One session option: its long name, --help group and help (without the default).
struct SessionOptionSpec {
  std::string_view name;   ///< "--tf"
  std::string_view group;  ///< "Input/output", "Camera", "LOD", "Probes", "Surface", "Memory", …
  std::string_view help;   ///< what it means, the same in every command
};

/// Every session option, in --help order. Never throws.
const std::vector<SessionOptionSpec>& session_options();

/// The row named `name` ("--tf"); asserts it exists (a programmer's typo). Never throws.
const SessionOptionSpec& session_option(std::string_view name);

/// Adds row `name` to c, storing into value, with the command's default stated in the help
/// (`default_text` empty: none stated), under the row's group. Returns the option (for a check).
/// Never throws.
template <typename T>
CLI::Option* add_session_option(CLI::App* c, std::string_view name, T& value,
                                const std::string& default_text) {
  const SessionOptionSpec& s = session_option(name);
  std::string help(s.help);
  if (!default_text.empty()) help += " (default " + default_text + ")";
  return c->add_option(std::string(name), value, help)->group(std::string(s.group));
}

/// --lod's value as the adaptive cut's: "on" is "auto" (the word play used). Never throws.
std::string lod_word(const std::string& text);

}  // namespace tspcli
