// The whole-tree evaluation of one metric: every TSP node's result under one transfer function
// (the reference metric reads the bricks, the others only the statistics).
#pragma once
#include "tsp/metric/metric.h"
#include "tsp/store/brick_store.h"

namespace tsp {

/// Computes metric for every node of tree under tf, with `threads` workers (0 = all cores).
/// The reference metric reads every voxel through bricks (UsageError when bricks is null);
/// the others use only the tree's statistics. Throws what bricks->read_brick throws.
MetricResult compute_errors(Metric metric, const TspTree& tree, const TransferFunction& tf,
                            const BrickStore* bricks = nullptr, int threads = 0);

}  // namespace tsp
