// The TF editor's histogram (src/player/tf_histogram.h): a skewed field whose colour range is
// fitted to its bulk falls in two or three of the file's 256 stored bins; the editor counts
// that range afresh from a step's samples, so its bars show the data.
#include "player/tf_histogram.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "support/function_tsp.h"
#include "tsp/store/tsp_file.h"

namespace {

using namespace tspplayer;

int nonempty(const EditorHistogram& h) {
  return int(std::count_if(h.counts.begin(), h.counts.end(), [](double c) { return c > 0; }));
}

TEST(PlayerTfHistogram, ASkewedFieldsBulkIsCountedAfreshOverTheDomain) {
  // Values 0.5 .. 0.51 (a smooth ramp over the grid) but for one corner at 0 and one at 1: the
  // quantization range is [0, 1], and the bulk fills under three of the 256 stored bins.
  const auto f = [](int x, int y, int z, int) -> float {
    if (x == 0 && y == 0 && z == 0) return 0.f;
    if (x == 31 && y == 31 && z == 31) return 1.f;
    return 0.5f + 0.01f * float(x + 32 * y + 1024 * z) / 32767.f;
  };
  const auto file = tsp::TspFile::open(tsptest::build_function_tsp("skewed", {32, 32, 32}, f));
  const tsp::ValueRange bulk{0.5, 0.51};
  int stored_in_bulk = 0;
  const tsp::ValueRange q = file->tree().value_range();
  for (std::size_t i = 0; i < file->histogram().size(); ++i) {
    const double v0 = q.lo + (q.hi - q.lo) * double(i) / 256, v1 = v0 + (q.hi - q.lo) / 256;
    stored_in_bulk += file->histogram()[i] > 0 && v1 > bulk.lo && v0 < bulk.hi;
  }
  EXPECT_LE(stored_in_bulk, 4);  // what the editor drew before: three or four bars
  const EditorHistogram h = editor_histogram(*file, 0, bulk, 100);
  EXPECT_EQ(h.step, 0);
  EXPECT_GE(nonempty(h), 95);  // the ramp fills every bin
  double total = 0;
  for (double c : h.counts) total += c;
  EXPECT_GE(total, 32.0 * 32 * 32 - 2);  // every sample inside the bulk (shared faces twice)
  // Over the whole range the stored histogram is enough: redistributed, every sample counted.
  const EditorHistogram all = editor_histogram(*file, 0, q, 64);
  EXPECT_EQ(all.step, -1);
  double stored = 0, shown = 0;
  for (std::uint64_t c : file->histogram()) stored += double(c);
  for (double c : all.counts) shown += c;
  EXPECT_NEAR(shown, stored, 1e-6 * stored);
}

}  // namespace
