// tspplay diff A.png B.png [--json] [-o DIFF.png]: per-pixel ΔE*uv between two images.
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/commands.h"
#include "tsp/core/json_text.h"
#include "tsp/core/temp_output.h"
#include "tsp/report/image.h"
#include "tsp/report/image_diff.h"

namespace tspcli {
namespace {

struct DiffArgs {
  std::string a, b, out;
  bool json = false;
};

const CommandRegistrar reg(60, [](CLI::App& app) {
  auto* c = app.add_subcommand("diff", "Colour difference (CIE L*u*v* ΔE) of two PNG images");
  auto a = std::make_shared<DiffArgs>();
  c->add_option("a", a->a, "First PNG")->required();
  c->add_option("b", a->b, "Second PNG")->required();
  c->add_flag("--json", a->json, "Print JSON (mean, p99, max, pixels, width, height)");
  c->add_option("-o,--output", a->out,
                "Write a grey difference image (white = ΔE ≥ 10) to this PNG");
  c->callback([a] {
    const tsp::InputGuard inputs({a->a, a->b});  // -o must not replace either image
    if (!a->out.empty()) tsp::check_output_path(a->out);  // before any work
    const tsp::Image ia = tsp::read_png(a->a), ib = tsp::read_png(a->b);
    tsp::Image diff;
    const tsp::DiffStats s = tsp::diff_images(ia, ib, a->out.empty() ? nullptr : &diff, a->a, a->b);
    if (!a->out.empty()) tsp::write_png(a->out, diff);
    if (a->json) {
      std::cout << tsp::json_text(nlohmann::json(s), 2) << "\n";
    } else {
      std::printf("%dx%d pixels, ΔE*uv (CIE L*u*v*): mean %.4f  p99 %.4f  max %.4f\n", s.width,
                  s.height, s.mean, s.p99, s.max);
    }
  });
});

}  // namespace
}  // namespace tspcli
