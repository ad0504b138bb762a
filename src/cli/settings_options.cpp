#include "cli/settings_options.h"

#include <cassert>

#include "render/settings_table.h"

namespace tspcli {

void SettingsOptions::add_to(CLI::App* c) {
  for (const tspgl::SettingSpec& spec : tspgl::settings_table()) {
    const std::string name(spec.name);
    std::string help(spec.help);
    if (spec.kind == tspgl::SettingKind::number) {
      if (!spec.unit.empty()) help += "; in " + std::string(spec.unit);
    } else {
      help += ": ";
      for (std::size_t i = 0; i < spec.choices.size(); ++i)
        help += (i ? "|" : "") + std::string(spec.choices[i]);
    }
    help += " (default " + spec.get(defaults_) + ")";
    CLI::Option* o = c->add_option("--" + name, texts_[name], help)
                         ->group(tspgl::group_title(spec.group));
    o->type_name(spec.kind == tspgl::SettingKind::number ? "NUMBER" : "WORD");
    options_.emplace_back(name, o);
  }
}

tspgl::RenderSettings SettingsOptions::apply() const {
  tspgl::RenderSettings s = defaults_;
  for (const auto& [name, o] : options_)
    if (o->count() > 0)
      tspgl::set_setting(s, *tspgl::find_setting(name), texts_.at(name), "--" + name);
  tspgl::validate(s);
  return s;
}

std::vector<std::string> SettingsOptions::given() const {
  std::vector<std::string> out;
  for (const auto& [name, o] : options_)
    if (o->count() > 0) out.push_back("--" + name);
  return out;
}

CLI::Option* on_off_option(CLI::App* c, const std::string& name, std::string& value,
                           const std::string& help) {
  return c->add_option(name, value, help + ": on|off, alone: on (default " + value + ")")
      ->expected(0, 1)
      ->default_str("on")
      ->check(CLI::IsMember({"on", "off"}));
}

void set_groups(CLI::App* c,
                const std::vector<std::pair<std::string, std::vector<std::string>>>& groups) {
  for (const auto& [group, names] : groups)
    for (const std::string& name : names) {
      CLI::Option* o = c->get_option_no_throw(name);
      assert(o && "set_groups: no such option");
      if (o) o->group(group);
    }
}

}  // namespace tspcli
