// tspplay build INPUT -o OUT.tsp: bricks and TSP tree from a time series.
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/progress_bar.h"
#include "tsp/build.h"
#include "tsp/error.h"
#include "tsp/tsp_file.h"

namespace tspcli {
namespace {

struct BuildArgs {
  std::string input, output, field, range, raw_dims, raw_type = "f32";
  int brick = tsp::kDefaultBrickSize;
  int threads = 0;
  bool big_endian = false;
};

// Set by SIGINT/SIGTERM; the progress callback turns it into an exception, so the build unwinds
// and removes its temporary file instead of leaving it behind.
volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void on_interrupt(int) {
  g_interrupted = 1;
}

double parse_number(const std::string& text, const std::string& option) {
  char* end = nullptr;
  double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size())
    throw tsp::UsageError(option + ": '" + text + "' is not a number");
  return v;
}

// "LO:HI" → a range; the builder checks LO < HI.
tsp::ValueRange parse_range(const std::string& text) {
  auto colon = text.find(':', 1);  // a leading '-' is a sign, never the separator
  if (colon == std::string::npos)
    throw tsp::UsageError("--range " + text + ": expected LO:HI, e.g. --range=-5:40");
  return {parse_number(text.substr(0, colon), "--range"),
          parse_number(text.substr(colon + 1), "--range")};
}

// "X,Y,Z" → grid size.
tsp::Dims parse_dims(const std::string& text) {
  int v[3];
  std::size_t pos = 0;
  for (int i = 0; i < 3; ++i) {
    std::size_t next = text.find(',', pos);
    if ((i < 2) != (next != std::string::npos))
      throw tsp::UsageError("--raw-dims " + text + ": expected X,Y,Z");
    double d =
        parse_number(text.substr(pos, next == std::string::npos ? next : next - pos), "--raw-dims");
    if (d < 1 || d != int(d))
      throw tsp::UsageError("--raw-dims " + text + ": sizes must be positive integers");
    v[i] = int(d);
    pos = next + 1;
  }
  return {v[0], v[1], v[2]};
}

void run_build(const BuildArgs& a) {
  tsp::SourceOptions so;
  so.field = a.field;
  if (!a.raw_dims.empty()) so.raw_dims = parse_dims(a.raw_dims);
  so.raw_type = a.raw_type == "u8"    ? tsp::RawType::u8
                : a.raw_type == "u16" ? tsp::RawType::u16
                                      : tsp::RawType::f32;
  so.raw_big_endian = a.big_endian;

  tsp::BuildOptions bo;
  bo.brick_size = a.brick;
  bo.threads = a.threads;
  bo.field_name = a.field;
  if (!a.range.empty()) bo.range = parse_range(a.range);
  auto source = tsp::open_source(a.input, so);
  ProgressBar bar;
  bo.progress = [&bar](const std::string& phase, std::int64_t done, std::int64_t total) {
    if (g_interrupted) throw tsp::Error("interrupted; no output written");
    bar.update(phase, done, total);
  };
  auto old_int = std::signal(SIGINT, on_interrupt);
  auto old_term = std::signal(SIGTERM, on_interrupt);
  tsp::BuildReport r;
  try {
    r = tsp::build_tsp_file(*source, a.output, bo);
  } catch (...) {
    bar.finish();
    std::signal(SIGINT, old_int);
    std::signal(SIGTERM, old_term);
    throw;
  }
  bar.finish();
  std::signal(SIGINT, old_int);
  std::signal(SIGTERM, old_term);

  if (r.nonfinite_count > 0)
    std::fprintf(
        stderr,
        "tspplay: warning: %lld NaN/Inf samples replaced (NaN and -Inf by %g, +Inf by %g)\n",
        static_cast<long long>(r.nonfinite_count), r.value_range.lo, r.value_range.hi);
  auto file = tsp::TspFile::open(a.output);
  const tsp::TspTree& tree = file->tree();
  const double mb = double(r.source_bytes) / 1e6;
  std::printf("wrote %s: %s voxels, %d steps, brick %d: %d bricks, %d TSP nodes\n",
              a.output.c_str(), tsp::to_string(tree.octree().dims()).c_str(), tree.time().steps(),
              tree.octree().brick_size(), tree.octree().brick_count(), tree.size());
  std::printf("value range [%g, %g], data range [%g, %g]; %.1f MB in %.2f s (%.1f MB/s)\n",
              r.value_range.lo, r.value_range.hi, r.data_range.lo, r.data_range.hi, mb, r.seconds,
              r.seconds > 0 ? mb / r.seconds : 0.0);
}

const CommandRegistrar reg(10, [](CLI::App& app) {
  auto* c = app.add_subcommand("build", "Build a .tsp file (bricks + TSP tree with statistics)");
  auto a = std::make_shared<BuildArgs>();
  c->add_option("input", a->input, "Time series: .h5/.nc/.hdf, .pvd/.vti.series/.vti, raw pattern")
      ->required();
  c->add_option("-o,--output", a->output, "The .tsp file to write")->required();
  c->add_option("--field", a->field, "Field (dataset/variable/array) to read");
  c->add_option("--brick", a->brick, "Brick edge in samples, a power of two (default 32)");
  c->add_option("--range", a->range, "Quantization range LO:HI (default: the data's range)");
  c->add_option("--raw-dims", a->raw_dims, "Raw input: grid size X,Y,Z");
  c->add_option("--raw-type", a->raw_type, "Raw input: element type u8|u16|f32")
      ->check(CLI::IsMember({"u8", "u16", "f32"}));
  c->add_flag("--big-endian", a->big_endian, "Raw input: big-endian samples");
  c->add_option("--threads", a->threads, "Worker threads (default: all cores)");
  c->callback([a] { run_build(*a); });
});

}  // namespace
}  // namespace tspcli
