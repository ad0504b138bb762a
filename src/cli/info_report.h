// What `tspplay info` reports about a .tsp file, as text or JSON.
#pragma once
#include <nlohmann/json.hpp>

#include "tsp/store/tsp_file.h"

namespace tspcli {

/// The info JSON: dims, steps, brick, counts, ranges, per-level errors; with_nodes adds `nodes`.
nlohmann::json info_json(const tsp::TspFile& f, bool with_nodes);

/// Prints the human summary (and with with_nodes a table of every TSP node) to stdout.
void print_info(const tsp::TspFile& f, bool with_nodes);

}  // namespace tspcli
