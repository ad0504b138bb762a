// Fuzz target: a PNG as `diff` reads it (tsp::read_png through the input gate: any colour type
// and bit depth, its decoded size checked before anything is allocated), then compared with
// itself as `diff` compares two frames (every ΔE must be 0).
#include <cstdlib>

#include "fuzz_input.h"
#include "tsp/report/image.h"
#include "tsp/report/image_diff.h"

namespace {
// Larger images are decoded but not compared (the comparison is linear in pixels; this keeps
// executions fast).
constexpr std::int64_t kMaxComparedPixels = 1 << 16;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = tspfuzz::write_input("input.png", data, size);
  tspfuzz::expect_clean([&] {
    const tsp::Image img = tsp::read_png(path);
    if (img.pixels() > kMaxComparedPixels) return;
    const tsp::DiffStats d = tsp::diff_images(img, img);
    if (d.max != 0) std::abort();  // an image differs from itself: a bug
  });
  return 0;
}
