// tspplay generate [NAME] -o out.h5 [--dims X,Y,Z] [--steps T] [--seed S] [--gzip L] | --list
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include "cli/args.h"
#include "cli/commands.h"
#include "tsp/core/error.h"
#include "tsp/core/stopwatch.h"
#include "tsp/source/hdf5_writer.h"
#include "tsp/source/procedural/generate.h"

namespace tspcli {
namespace {

struct GenerateArgs {
  std::string name = "shock";
  std::string output;
  std::string dims;
  std::string steps;
  std::string seed;
  std::string gzip;
  bool list = false;
};

void print_list() {
  for (const auto& d : tsp::list_datasets())
    std::printf("%-8s %s (default %s, %d steps)\n", d.name.c_str(), d.description.c_str(),
                tsp::to_string(d.default_dims).c_str(), d.default_steps);
}

void run(const GenerateArgs& a) {
  if (a.list) {
    print_list();
    return;
  }
  if (a.output.empty()) throw tsp::UsageError("generate: expected an output file, -o out.h5");
  tsp::GenerateOptions opt;
  if (!a.dims.empty()) opt.dims = parse_dims(a.dims, "--dims", tsp::kMaxGeneratedEdge, true);
  if (!a.steps.empty())
    opt.steps =
        int(parse_integer(a.steps, "--steps", 1, tsp::kMaxGeneratedSteps,
                          "a step count in [1, " + std::to_string(tsp::kMaxGeneratedSteps) + "]"));
  if (!a.seed.empty())
    opt.seed =
        std::uint64_t(parse_integer(a.seed, "--seed", 0, std::numeric_limits<long long>::max(),
                                    "a non-negative integer below 2^63"));
  int gzip = 0;
  if (!a.gzip.empty())
    gzip = int(parse_integer(a.gzip, "--gzip", 0, tsp::kMaxGzipLevel, "a level 0..9"));
  auto source = tsp::make_generated_source(a.name, opt);
  const tsp::Stopwatch watch;
  tsp::write_generated_dataset(*source, a.output, gzip);
  const double secs = watch.seconds();
  std::printf("wrote %s: /%s %s x %d steps, float32, seed %llu (%.2f s)\n", a.output.c_str(),
              source->name().c_str(), tsp::to_string(source->dims()).c_str(), source->steps(),
              static_cast<unsigned long long>(source->seed()), secs);
}

CommandRegistrar reg(10, [](CLI::App& app) {
  auto args = std::make_shared<GenerateArgs>();
  auto* c = app.add_subcommand("generate", "Write a built-in procedural dataset to an HDF5 file");
  c->add_option("name", args->name, "Built-in dataset name, default shock (see --list)");
  c->add_option("-o,--output", args->output, "Output .h5 file; dataset /NAME, shape (T,Z,Y,X)");
  c->add_option("--dims", args->dims, "Grid size X,Y,Z or N (default 64,64,64)");
  c->add_option("--steps", args->steps, "Number of time steps (default 32)");
  c->add_option("--seed", args->seed, "Noise seed (default 1)");
  c->add_option("--gzip", args->gzip, "Compress with shuffle+gzip at this level 1..9 (default 0)");
  c->add_flag("--list", args->list, "List the built-in datasets and exit");
  c->callback([args] { run(*args); });
});

}  // namespace
}  // namespace tspcli
