#include "tsp/source/procedural/generate.h"

#include <algorithm>
#include <cassert>
#include <vector>

#include "tsp/core/error.h"
#include "tsp/core/parallel_for.h"
#include "tsp/source/hdf5_writer.h"
#include "tsp/source/procedural/procedural_source.h"

namespace tsp {
namespace {

constexpr Dims kDefaultGeneratedDims{64, 64, 64};
constexpr int kDefaultGeneratedSteps = 32;

using Factory = std::unique_ptr<GeneratedSource> (*)(Dims, int, std::uint64_t, int);
struct Entry {
  DatasetInfo info;
  Factory make;
};

const std::vector<Entry>& registry() {
  static const std::vector<Entry> r = {
      {{"shock",
        "curved shock front sweeping +x into empty gas, turbulent evolving wake behind it, "
        "a fixed pillar and layered ground that never change",
        kDefaultGeneratedDims, kDefaultGeneratedSteps},
       &make_shock},
      {{"vortex",
        "signed compact blobs orbiting a vertical axis at different speeds, each with a "
        "spinning lobed pattern; mostly empty, nothing static",
        kDefaultGeneratedDims, kDefaultGeneratedSteps},
       &make_vortex},
  };
  return r;
}

}  // namespace

std::vector<DatasetInfo> list_datasets() {
  std::vector<DatasetInfo> out;
  for (const auto& e : registry()) out.push_back(e.info);
  return out;
}

std::unique_ptr<GeneratedSource> make_generated_source(const std::string& name,
                                                       const GenerateOptions& options) {
  const Entry* entry = nullptr;
  std::string known;
  for (const auto& e : registry()) {
    if (e.info.name == name) entry = &e;
    known += (known.empty() ? "" : ", ") + e.info.name;
  }
  if (!entry)
    throw UsageError("unknown built-in dataset '" + name + "', expected one of: " + known);
  Dims dims = options.dims.value_or(entry->info.default_dims);
  for (int a = 0; a < 3; ++a) {
    if (dims[a] < 1 || dims[a] > kMaxGeneratedEdge)
      throw UsageError("dataset '" + name + "': dims " + to_string(dims) +
                       ", expected every edge in [1, " + std::to_string(kMaxGeneratedEdge) + "]");
  }
  int steps = options.steps.value_or(entry->info.default_steps);
  if (steps < 1 || steps > kMaxGeneratedSteps)
    throw UsageError("dataset '" + name + "': steps " + std::to_string(steps) +
                     ", expected a count in [1, " + std::to_string(kMaxGeneratedSteps) + "]");
  // Products in 64 bits (each factor is at most 2048 or 4096), before anything is allocated.
  const std::int64_t step_samples = dims.count();
  if (step_samples > kMaxGeneratedStepSamples)
    throw UsageError("dataset '" + name + "': dims " + to_string(dims) + " make " +
                     std::to_string(step_samples) + " samples per step, more than the " +
                     std::to_string(kMaxGeneratedStepSamples) +
                     " (4 GiB of float32, e.g. 1024x1024x1024) a step may hold in memory");
  if (step_samples * steps > kMaxGeneratedSamples)
    throw UsageError("dataset '" + name + "': dims " + to_string(dims) + " x " +
                     std::to_string(steps) + " steps make " + std::to_string(step_samples * steps) +
                     " samples, more than the " + std::to_string(kMaxGeneratedSamples) +
                     " (256 GiB of float32) generate writes");
  return entry->make(dims, steps, options.seed, options.threads);
}

ProceduralSource::ProceduralSource(std::string name, Dims dims, int steps, std::uint64_t seed,
                                   int threads)
    : name_(std::move(name)), dims_(dims), steps_(steps), seed_(seed), threads_(threads) {
  threads_ = resolve_threads(threads_);
}

std::string ProceduralSource::describe() const {
  return "built-in dataset " + name_ + " (seed " + std::to_string(seed_) + ", " + to_string(dims_) +
         ", " + std::to_string(steps_) + " steps)";
}

void ProceduralSource::read_step(int t, std::span<float> out) { read_slab(t, 0, dims_.z, out); }

void ProceduralSource::read_slab(int t, int z0, int z1, std::span<float> out) {
  assert(t >= 0 && t < steps_ && 0 <= z0 && z0 < z1 && z1 <= dims_.z);
  const std::int64_t plane = std::int64_t(dims_.x) * dims_.y;
  assert(std::int64_t(out.size()) == plane * (z1 - z0));
  double tau = normalised_time(t, steps_);
  // Contiguous z-slabs, one per worker (values do not depend on the split).
  const int slab = (z1 - z0 + threads_ - 1) / threads_;
  parallel_for(z1 - z0, slab, threads_, [&](int, std::int64_t a, std::int64_t b) {
    fill_slab(tau, z0 + int(a), z0 + int(b), out.data() + a * plane);
  });
}

void write_generated_dataset(GeneratedSource& source, const std::string& path, int gzip_level) {
  Hdf5WriteOptions w;
  w.dataset = source.name();
  w.gzip_level = gzip_level;
  w.attributes = {{"generator", source.name()},
                  {"seed", source.seed()},
                  {"generator_version", std::int64_t(kGeneratorVersion)}};
  write_hdf5(source, path, w);
}

}  // namespace tsp
