// tspplay info FILE.tsp [--json] [--nodes]: what a .tsp file holds.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/info_report.h"
#include "tsp/core/json_text.h"
#include "tsp/store/tsp_file.h"

namespace tspcli {
namespace {

struct InfoArgs {
  std::string file, field;
  bool json = false;
  bool nodes = false;
};

const CommandRegistrar reg(20, [](CLI::App& app) {
  auto* c = app.add_subcommand("info", "Describe a .tsp file");
  auto a = std::make_shared<InfoArgs>();
  c->add_option("file", a->file, "The .tsp file")->required();
  c->add_flag("--json", a->json, "Print JSON");
  c->add_flag("--nodes", a->nodes, "Include every TSP node's statistics");
  c->add_option("--field", a->field, "A file with several fields: describe this one (default: the first)");
  c->callback([a] {
    auto f = tsp::TspFile::open(a->file, a->field);
    if (a->json)
      std::cout << tsp::json_text(info_json(*f, a->nodes), 2) << "\n";
    else
      print_info(*f, a->nodes);
  });
});

}  // namespace
}  // namespace tspcli
