// The render settings a user sets, listed once: name, kind, default, range, unit, help and
// group of every knob of RenderSettings. From this table come the CLI options of `render` and
// `play` (cli/settings_options.h), the player's script actions and panel widgets, the settings
// in frames.json and the player's stats, and the `render` options that reproduce a
// configuration (knob_search's render_options). One parser and one validation for all of them.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "render/render_settings.h"

namespace tspgl {

/// What a setting's value is.
enum class SettingKind {
  number,  ///< a finite number in [lo, hi]
  toggle,  ///< on or off
  choice,  ///< one of a few words
};

/// Which group of options a setting is listed in (render --help).
enum class SettingGroup {
  quality,      ///< what the picture shows: tolerances, spacing, sampling
  compositing,  ///< how textured boxes are drawn
  memory,       ///< budgets
  diagnostics,  ///< ablation switches (the paper's rules, our optimisations off)
};

/// The group's heading in --help ("Quality", "Compositing", "Memory", "Diagnostics").
const char* group_title(SettingGroup g);

/// One row of the table.
struct SettingSpec {
  std::string_view name;  ///< CLI option --NAME, script action NAME, JSON key NAME with '_'
  SettingKind kind = SettingKind::number;
  SettingGroup group = SettingGroup::quality;
  std::string_view unit;                  ///< numbers: the unit, for help and widgets
  double lo = 0, hi = 0;                  ///< numbers: the accepted range (hi may be infinite)
  std::vector<std::string_view> choices;  ///< choices: the words; toggles: {"off", "on"}
  /// Numbers: the player's slider range (logarithmic; a typed value may use all of [lo, hi]).
  double ui_lo = 0, ui_hi = 0;
  std::string_view help;                  ///< one sentence, without the default
  /// The setting's value in s as text: a number (17 significant digits, so it parses back to
  /// the same double), "on"/"off" or the choice's word.
  std::string (*get)(const RenderSettings& s) = nullptr;
  /// Stores an already validated value into s: a number, or the index into choices.
  void (*set)(RenderSettings& s, double value) = nullptr;
  /// The value's key in JSON: name with '-' as '_'.
  std::string json_key() const;
};

/// Every setting, in the order --help and the panels list them. Never throws.
const std::vector<SettingSpec>& settings_table();

/// The row named name ("spacing", "spatial-tol", ...), or null. Never throws.
const SettingSpec* find_setting(std::string_view name);

/// Parses text as setting spec's value and stores it into s. Throws tsp::UsageError
/// "WHERE TEXT: expected ..." naming the accepted range, unit or words (where: "--spacing",
/// "script line 3: spacing").
void set_setting(RenderSettings& s, const SettingSpec& spec, const std::string& text,
                 const std::string& where);

/// Throws the tsp::UsageError set_setting gives for its text ("WHERE 'VALUE': expected ...")
/// unless s's value of spec lies in the row's range (a finite number in [lo, hi]).
void check_setting(const RenderSettings& s, const SettingSpec& spec, const std::string& where);

/// The setting's value in s as text (SettingSpec::get). Never throws.
std::string get_setting(const RenderSettings& s, const SettingSpec& spec);

/// The setting's default (a default-constructed RenderSettings') as text. Never throws.
std::string default_text(const SettingSpec& spec);

/// The `render` options that give s, one "--NAME VALUE" per setting that differs from the
/// default, in table order ("" when s is the default). Never throws.
std::string to_options(const RenderSettings& s);

/// Every setting of s as JSON: numbers, booleans for toggles, words for choices (the frames.json
/// and stats keys). Never throws.
nlohmann::json settings_json(const RenderSettings& s);

}  // namespace tspgl
