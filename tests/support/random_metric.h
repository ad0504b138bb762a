// Random per-node errors and transparency for planner and cache tests.
#pragma once
#include <cmath>
#include <random>

#include "tsp/metric/metric.h"
#include "tsp/tree/tsp_tree.h"

namespace tsptest {

/// Errors grow towards the roots of the octree and the time tree (factor 1.25 a level) so that
/// traversals mix levels and span lengths; with zero_share > 0 that share of the errors is
/// exactly 0; 15% of the nodes are transparent.
inline tsp::MetricResult random_metric(const tsp::TspTree& tree, std::mt19937& rng,
                                       float zero_share = 0.f) {
  std::uniform_real_distribution<float> u(0.f, 1.f);
  tsp::MetricResult m;
  const int n = tree.size();
  m.errors.spatial.resize(n);
  m.errors.temporal.resize(n);
  m.mean_colour.resize(n);
  m.transparent.resize(n);
  auto error = [&](float scale) {
    if (zero_share > 0 && u(rng) < zero_share) return 0.f;
    return u(rng) * scale;
  };
  for (int id = 0; id < n; ++id) {
    const int above = tree.octree().depth() - tree.octree().node(tree.octree_of(id)).level +
                      tree.time().depth() - tree.time().level(tree.time_of(id));
    const float scale = std::pow(1.25f, float(above));
    m.errors.spatial[id] = error(scale);
    m.errors.temporal[id] = error(scale);
    m.transparent[id] = u(rng) < 0.15f;
  }
  return m;
}

}  // namespace tsptest
