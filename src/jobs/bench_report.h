// The files `tspplay bench` writes: table3.csv, table4.csv, table5.csv and report.json, rows
// added as the runs finish, then written atomically (docs/bench.md names every column).
#pragma once
#include <array>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "jobs/knob_search.h"
#include "jobs/timing.h"
#include "jobs/tolerance_search.h"

namespace tspgl {

/// Rows of the three tables and the JSON report. Not thread-safe.
class BenchReport {
 public:
  /// Starts the report with header's fields (file, dims, size, …) and empty tables.
  explicit BenchReport(nlohmann::json header);
  /// A tolerance search's record: its error span and every evaluation made.
  void add_search(const std::string& tf, const std::string& metric, const ErrorSpan& span,
                  const nlohmann::json& evaluations);
  /// Table 3's baseline row.
  void add_baseline(const std::string& tf, const Timing& b);
  /// Table 3's zero-tolerance TSP row (and its Table-5 row).
  void add_zero_tolerance(const std::string& tf, const std::string& metric, const char* cache,
                          const Timing& t, double baseline_ms, double mean_de);
  /// Table 4's row: the fastest configuration of `renderer` ("baseline" or "tsp", metric empty
  /// for the baseline) within target, timed with the cache on (its Table-5 row too); best null
  /// when no configuration met the target. best_baseline_ms: the fastest non-TSP time at this
  /// target; reference_ms: the full-quality picture's.
  void add_best(const std::string& tf, const std::string& renderer, const std::string& metric,
                double target, const KnobCandidate* best, const Timing* t, tsp::Metric options_metric,
                double best_baseline_ms, double reference_ms);
  /// Names a plot file written beside the report.
  void add_plot(const std::string& file);
  /// Writes table3.csv, table4.csv, table5.csv and report.json into dir, each atomically, and
  /// returns the report. Throws tsp::IoError.
  nlohmann::json write(const std::string& dir);

 private:
  nlohmann::json report_;
  std::ostringstream t3_, t4_, t5_;
  void add_classes(const std::string& tf, const std::string& metric, const char* cache,
                   double tol, double target, const Timing& t);
};

/// A number as the CSV files write it (%.6g). Never throws.
std::string fmt(double v);

}  // namespace tspgl
