// tsp/source/procedural: the built-in datasets; may include core/ and source/.
// Built-in procedural time-varying datasets: VolumeSources computed on the fly, so builds, tests
// and benchmarks can use realistic-looking data without a file. See docs/datasets.md.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tsp/core/types.h"
#include "tsp/source/procedural/generated_source.h"

namespace tsp {

/// Bumped whenever any dataset's values change for the same name, seed, dims and steps.
inline constexpr int kGeneratorVersion = 1;
/// Largest grid edge and step count accepted by the generator.
inline constexpr int kMaxGeneratedEdge = 2048;
inline constexpr int kMaxGeneratedSteps = 4096;
/// Largest step the generator makes (samples; one step is held in memory as float32: 4 GiB).
inline constexpr std::int64_t kMaxGeneratedStepSamples = std::int64_t(1) << 30;
/// Largest dataset the generator writes (samples over all steps: 256 GiB of float32).
inline constexpr std::int64_t kMaxGeneratedSamples = std::int64_t(1) << 36;
/// Seed used when none is given.
inline constexpr std::uint64_t kDefaultSeed = 1;

/// One built-in dataset: its name, a one-line description and its default size.
struct DatasetInfo {
  std::string name;
  std::string description;
  Dims default_dims;
  int default_steps = 0;
};

/// The built-in datasets, the default ("shock") first.
std::vector<DatasetInfo> list_datasets();

/// How to generate: size, time steps, seed and worker threads (all optional).
struct GenerateOptions {
  std::optional<Dims> dims;           ///< grid size; empty: the dataset's default
  std::optional<int> steps;           ///< number of steps; empty: the dataset's default
  std::uint64_t seed = kDefaultSeed;  ///< changes the noise patterns, not the geometry
  int threads = 0;                    ///< worker threads per read_step; 0: hardware concurrency
};

/// Makes the named built-in dataset. Throws UsageError for an unknown name (listing the known ones)
/// or dims/steps outside [1, kMaxGeneratedEdge] / [1, kMaxGeneratedSteps], a step of more than
/// kMaxGeneratedStepSamples or a dataset of more than kMaxGeneratedSamples samples.
std::unique_ptr<GeneratedSource> make_generated_source(const std::string& name,
                                                       const GenerateOptions& options = {});

/// Writes source to path as the HDF5 dataset /NAME (T,Z,Y,X) with its provenance attributes
/// (generator, seed, generator_version), atomically; gzip_level 0 = uncompressed.
/// Throws IoError/UsageError as write_hdf5 does.
void write_generated_dataset(GeneratedSource& source, const std::string& path, int gzip_level = 0);

}  // namespace tsp
