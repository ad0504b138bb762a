// The render settings table: every row parses what it writes, to_options lists exactly the
// settings that differ from the default (and parses back to the same value), the JSON has one
// key per row, and values outside a row's range are refused naming it and the range.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <vector>

#include "render/render_settings.h"
#include "render/settings_table.h"
#include "tsp/core/error.h"

namespace {

using namespace tspgl;

// Parses "--a x --b y" back through the table into a default RenderSettings.
RenderSettings parse_options(const std::string& options) {
  RenderSettings s;
  std::istringstream in(options);
  std::string name, value;
  while (in >> name >> value) {
    EXPECT_EQ(name.rfind("--", 0), 0u) << name;
    const SettingSpec* spec = find_setting(name.substr(2));
    EXPECT_NE(spec, nullptr) << name;
    if (spec) set_setting(s, *spec, value, name);
  }
  return s;
}

TEST(SettingsTable, NamesAreUniqueAndEveryRowIsComplete) {
  std::set<std::string> names;
  for (const SettingSpec& spec : settings_table()) {
    EXPECT_TRUE(names.insert(std::string(spec.name)).second) << spec.name;
    EXPECT_FALSE(spec.help.empty()) << spec.name;
    EXPECT_NE(spec.get, nullptr);
    EXPECT_NE(spec.set, nullptr);
    if (spec.kind == SettingKind::number) {
      EXPECT_LE(spec.lo, spec.hi) << spec.name;
      EXPECT_LE(spec.lo, spec.ui_lo) << spec.name;
      EXPECT_LT(spec.ui_lo, spec.ui_hi) << spec.name;
    } else {
      EXPECT_GE(spec.choices.size(), 2u) << spec.name;
    }
    EXPECT_EQ(find_setting(spec.name), &spec);
  }
  EXPECT_EQ(find_setting("no-such-setting"), nullptr);
}

TEST(SettingsTable, EveryValueParsesBackToItself) {
  for (const SettingSpec& spec : settings_table()) {
    std::vector<std::string> values;
    if (spec.kind == SettingKind::number)
      values = {default_text(spec), "0.1", "1", "3.0000000000000004"};
    else
      for (std::string_view c : spec.choices) values.emplace_back(c);
    for (const std::string& v : values) {
      RenderSettings s;
      if (spec.kind == SettingKind::number && (std::stod(v) < spec.lo || std::stod(v) > spec.hi))
        continue;
      set_setting(s, spec, v, spec.name.data());
      RenderSettings again;
      set_setting(again, spec, get_setting(s, spec), "again");
      EXPECT_EQ(again, s) << spec.name << " " << v;
    }
  }
}

TEST(SettingsTable, OptionsListWhatDiffersAndParseBack) {
  EXPECT_EQ(to_options(RenderSettings{}), "");
  RenderSettings s;
  s.spacing = 2;
  s.compositing = Compositing::slices;
  s.tol.temporal = 0.1;
  s.preintegrated = true;
  s.skip_transparent = false;
  s.upload_budget = 16 << 20;
  s.span_step = tsp::SpanStep::mean;
  const std::string o = to_options(s);
  EXPECT_EQ(o,
            "--temporal-tol 0.10000000000000001 --spacing 2 --span-step mean --compositing "
            "slices --preintegrated on --upload-budget 16 --skip-transparent off");
  EXPECT_EQ(parse_options(o), s);
}

TEST(SettingsTable, JsonHasOneKeyPerRowWithItsType) {
  RenderSettings s;
  s.exact_flat = false;
  const nlohmann::json j = settings_json(s);
  EXPECT_EQ(j.size(), settings_table().size());
  EXPECT_EQ(j["spacing"], 0.5);
  EXPECT_EQ(j["compositing"], "rays");
  EXPECT_EQ(j["flat"], "slices");
  EXPECT_EQ(j["reuse"], true);
  EXPECT_EQ(j["span_step"], "middle");
  EXPECT_EQ(j["skip_transparent"], true);
  EXPECT_EQ(j["spatial_tol"], 0.0);
}

TEST(SettingsTable, RefusesValuesOutsideTheRowNamingIt) {
  auto error_of = [](const std::string& name, const std::string& text) {
    RenderSettings s;
    try {
      set_setting(s, *find_setting(name), text, "--" + name);
    } catch (const tsp::UsageError& e) {
      EXPECT_EQ(s, RenderSettings{}) << "a refused value changes nothing";
      return std::string(e.what());
    }
    ADD_FAILURE() << name << " " << text << " accepted";
    return std::string();
  };
  EXPECT_EQ(error_of("spacing", "100"), "--spacing '100': expected a number in [0.015625, 64] (voxels)");
  EXPECT_EQ(error_of("spacing", "2x"), "--spacing '2x': expected a number in [0.015625, 64] (voxels)");
  EXPECT_EQ(error_of("spatial-tol", "-1"),
            "--spatial-tol '-1': expected a finite number >= 0 (metric error)");
  EXPECT_EQ(error_of("spatial-tol", "inf"),
            "--spatial-tol 'inf': expected a finite number >= 0 (metric error)");
  EXPECT_EQ(error_of("temporal-tol", "nan"),
            "--temporal-tol 'nan': expected a finite number >= 0 (metric error)");
  EXPECT_EQ(error_of("compositing", "voxels"),
            "--compositing 'voxels': expected slices, boxes or rays");
  EXPECT_EQ(error_of("reuse", "yes"), "--reuse 'yes': expected off or on");
  EXPECT_EQ(error_of("upload-budget", ""),
            "--upload-budget '': expected a number in [0, 1.04858e+06] (MiB)");
  // A long value is quoted in part.
  EXPECT_LT(error_of("flat", std::string(5000, 'x')).size(), 120u);
}

// validate() holds a RenderSettings built in code (not parsed) to the same rows: every number row
// just outside its range, or not finite, is refused with the message set_setting gives for that
// value's text; the values at the ends pass.
TEST(SettingsTable, ValidateRefusesWhatTheRowRefusesWithTheRowsMessage) {
  auto message_of = [](const RenderSettings& s) {
    try {
      validate(s);
    } catch (const tsp::UsageError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const double kNan = std::numeric_limits<double>::quiet_NaN(),
               kInf = std::numeric_limits<double>::infinity();
  int rows = 0;
  for (const SettingSpec& spec : settings_table()) {
    if (spec.kind != SettingKind::number) continue;
    ++rows;
    const std::string name = "--" + std::string(spec.name);
    const double below = spec.lo - (spec.lo == 0 ? 1 : spec.lo / 2);
    std::vector<double> bads{below, std::isinf(spec.hi) ? kNan : spec.hi * 2};
    if (spec.name != "upload-budget") bads.push_back(-kInf);  // (held as whole bytes)
    for (double bad : bads) {
      RenderSettings s;
      spec.set(s, bad);
      const std::string text = spec.get(s);  // (a byte count in MiB: its value as stored)
      RenderSettings scratch;
      std::string parsed = "accepted";
      try {
        set_setting(scratch, spec, text, name);
      } catch (const tsp::UsageError& e) {
        parsed = e.what();
      }
      EXPECT_NE(parsed, "accepted") << name << " " << text;
      EXPECT_EQ(message_of(s), parsed) << name << " " << text;
    }
    for (double good : {spec.lo, std::isinf(spec.hi) ? 1e300 : spec.hi}) {
      RenderSettings s;
      spec.set(s, good);
      EXPECT_EQ(message_of(s), "accepted") << name << " " << good;
    }
  }
  EXPECT_GE(rows, 8);  // tolerances, spacing, sampling-tol, refine-tol, render-scale, ...
  RenderSettings s;
  s.spacing = 100;
  EXPECT_EQ(message_of(s), "--spacing '100': expected a number in [0.015625, 64] (voxels)");
  s = {};
  s.upload_budget = -1;
  EXPECT_EQ(message_of(s).rfind("--upload-budget '-9.5367431640625e-07': expected a number in [0, ",
                                0),
            0u)
      << message_of(s);
}

// The sampling knobs' one reading: adaptive before pre-integration before refinement, the
// conflict refused by validate with the one message, and settled in favour of the knob just
// changed (the player's set command).
TEST(SamplingMode, ResolvedInOnePlaceWithOneConflictMessage) {
  RenderSettings s;
  s.refine_tol = 0;
  EXPECT_EQ(resolve_sampling(s), SamplingMode::segments);
  s.refine_tol = 0.02;
  EXPECT_EQ(resolve_sampling(s), SamplingMode::refined);
  s.preintegrated = true;
  EXPECT_EQ(resolve_sampling(s), SamplingMode::preintegrated);
  EXPECT_EQ(sampling_conflict(s), "");
  s.sampling_tol = 0.5;
  EXPECT_EQ(resolve_sampling(s), SamplingMode::adaptive);
  const std::string why = sampling_conflict(s);
  EXPECT_EQ(why, "--sampling-tol 0.5 with --preintegrated on: adaptive sampling uses the point "
                 "lookup; choose one");
  try {
    validate(s);
    ADD_FAILURE() << "validate accepted adaptive sampling with pre-integration";
  } catch (const tsp::UsageError& e) {
    EXPECT_EQ(std::string(e.what()), why);
  }
  RenderSettings a = s, b = s;
  EXPECT_NE(settle_sampling(a, "preintegrated"), "");
  EXPECT_TRUE(a.preintegrated);
  EXPECT_EQ(a.sampling_tol, 0);
  EXPECT_NE(settle_sampling(b, "sampling-tol"), "");
  EXPECT_FALSE(b.preintegrated);
  EXPECT_EQ(b.sampling_tol, 0.5);
  EXPECT_EQ(settle_sampling(a, "preintegrated"), "");  // nothing left to settle
  EXPECT_NO_THROW(validate(a));
  EXPECT_NO_THROW(validate(b));
}

}  // namespace
