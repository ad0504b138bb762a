// Every TSP node's statistics as columns by node id: the layout the .tsp file stores them in and
// the Python module hands out.
#pragma once
#include <vector>

#include "tsp/tree/tsp_tree.h"

namespace tsp {

/// NodeStats of every TSP node, one column per field, indexed by TSP node id.
struct StatsColumns {
  std::vector<double> mean;           ///< NodeStats::mean
  std::vector<double> std;            ///< NodeStats::std
  std::vector<float> min;             ///< NodeStats::min
  std::vector<float> max;             ///< NodeStats::max
  std::vector<float> spatial_error;   ///< NodeStats::spatial_error
  std::vector<float> temporal_error;  ///< NodeStats::temporal_error
};

/// tree's statistics as columns of tree.size() values.
StatsColumns stats_columns(const TspTree& tree);

/// Sets every node's statistics of tree from c (each column tree.size() long; asserted).
void set_stats(TspTree& tree, const StatsColumns& c);

}  // namespace tsp
