// The interface of the built-in procedural datasets: a VolumeSource that also names its dataset
// and seed (the provenance written with it). The factory is in generate.h.
#pragma once
#include <cstdint>
#include <string>

#include "tsp/source/volume_source.h"

namespace tsp {

/// A procedural VolumeSource. Values depend only on (name, seed, normalised position x/(X−1),
/// normalised time t/(T−1)), never on the thread count.
class GeneratedSource : public VolumeSource {
 public:
  /// The dataset's name ("shock", "vortex").
  virtual const std::string& name() const = 0;
  /// The seed the noise is derived from.
  virtual std::uint64_t seed() const = 0;
};

}  // namespace tsp
