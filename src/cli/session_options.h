// The session options (input, view, LOD, probes, TF, budgets, surface, quality): what a run of
// frames is drawn from and with besides the render settings' knobs. As the settings table does
// for the knobs (settings_options.h), this table gives each option one name, one meaning, one
// help and one field of SessionArgs, in every command that takes it (render, play, bench); each
// row states, in one place, which commands take it and each one's default, which --help shows.
#pragma once
#include <CLI/CLI.hpp>
#include <array>
#include <initializer_list>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace tspcli {

/// A command that takes session options.
enum class SessionCommand { render, play, bench };
/// How many SessionCommand values there are.
inline constexpr std::size_t kSessionCommands = 3;
/// "render", "play" or "bench". Never throws.
std::string_view to_string(SessionCommand c);

/// The session options' values as the command line gives them (text as typed; numbers where
/// CLI11 parses them): one struct for render, play and bench. A command's defaults:
/// session_defaults(command).
struct SessionArgs {
  std::string field, tf, tf_range;                    ///< --field, --tf, --tf-range
  std::string size, view, proportions, scale;         ///< --size, --view, --proportions, --scale
  std::vector<std::string> probes;                    ///< --probe (repeatable)
  std::string probe_op, probe_surface;                ///< --probe-op, --probe-surface on|off
  std::string surface_mesh, surface_field, surface_tf;  ///< --surface-mesh, -field, -tf
  std::string lod, lod_fallback, lod_filter;          ///< --lod, --lod-fallback, --lod-filter
  double target_fps = 0;                              ///< --target-fps (0: none)
  double quality = 0;                                 ///< --quality, mean ΔE (0: off)
  double texture_budget_mb = 0, ram_budget_mb = 0;    ///< --texture-budget, --ram-budget (MiB)
  std::string gl;                                     ///< --gl auto|egl|osmesa
  int gpu = -1;                                       ///< --gpu (−1: the default device)
};

/// Where a row's value lives in SessionArgs.
using SessionField =
    std::variant<std::string SessionArgs::*, std::vector<std::string> SessionArgs::*,
                 double SessionArgs::*, int SessionArgs::*>;

/// One command's use of a row: whether it takes the option, the value it starts from (as typed;
/// "" leaves the field as SessionArgs has it) and how --help states the default ("": the value
/// itself; both empty: none stated).
struct SessionDefault {
  bool taken = false;
  std::string_view value;
  std::string_view shown;
};

/// One session option: its long name, --help group, help (without the default), field,
/// accepted words (empty: any text the command checks) and each command's default.
struct SessionOptionSpec {
  std::string_view name;   ///< "--tf"
  std::string_view group;  ///< "Input/output", "Camera", "LOD", "Probes", "Surface", "Memory", …
  std::string_view help;   ///< what it means, the same in every command
  SessionField field;      ///< where it is stored
  std::vector<std::string_view> choices;  ///< the words it accepts, checked by CLI11
  std::array<SessionDefault, kSessionCommands> defaults;  ///< by SessionCommand
  /// command's default (taken or not). Never throws.
  const SessionDefault& in(SessionCommand command) const {
    return defaults[std::size_t(command)];
  }
};

/// Every session option, in --help order. Never throws.
const std::vector<SessionOptionSpec>& session_options();

/// The row named `name` ("--tf"); asserts it exists (a programmer's typo). Never throws.
const SessionOptionSpec& session_option(std::string_view name);

/// The help --help shows for row s in command: the row's help and the command's default. Never
/// throws but std::bad_alloc.
std::string session_help(const SessionOptionSpec& s, SessionCommand command);

/// SessionArgs holding command's defaults for every row it takes (the others as SessionArgs
/// has them). Never throws but std::bad_alloc.
SessionArgs session_defaults(SessionCommand command);

/// Adds to c every row command takes but those named in `except`, storing into a's fields,
/// under the rows' groups, with session_help's text and the rows' choices. Never throws.
void add_session_options(CLI::App* c, SessionCommand command, SessionArgs& a,
                         std::initializer_list<std::string_view> except = {});

/// Adds row `name` (one command takes) to c, storing into value instead of a SessionArgs field
/// (bench's several --tf), with session_help's text. Returns the option. Never throws.
template <typename T>
CLI::Option* add_session_option(CLI::App* c, SessionCommand command, std::string_view name,
                                T& value) {
  const SessionOptionSpec& s = session_option(name);
  return c->add_option(std::string(name), value, session_help(s, command))
      ->group(std::string(s.group));
}

/// --lod's value as the adaptive cut's: "on" is "auto" (the word play used). Never throws.
std::string lod_word(const std::string& text);

}  // namespace tspcli
