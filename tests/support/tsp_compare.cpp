#include "support/tsp_compare.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "tsp/store/tsp_file.h"

namespace tsptest {
namespace {

namespace fs = std::filesystem;

template <class T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

}  // namespace

void expect_same_build(const fs::path& a_path, const fs::path& b_path, int ranks,
                       const std::string& field) {
  auto a = tsp::TspFile::open(a_path.string(), field);
  auto b = tsp::TspFile::open(b_path.string(), field);
  const tsp::TspTree& ta = a->tree();
  const tsp::TspTree& tb = b->tree();
  ASSERT_EQ(ta.size(), tb.size());
  ASSERT_EQ(ta.octree().stored_brick_count(), tb.octree().stored_brick_count());
  const int steps = ta.time().steps();
  std::vector<std::uint16_t> ca, cb;
  std::vector<std::uint8_t> ia, ib;
  const bool stencil = ta.has_stencil();
  ASSERT_EQ(stencil, tb.has_stencil());
  if (stencil) {
    const auto fa = ta.inside_fractions(), fb = tb.inside_fractions();
    ASSERT_EQ(fa.size(), fb.size());
    EXPECT_EQ(0, std::memcmp(fa.data(), fb.data(), fa.size_bytes())) << "inside fractions";
  }
  for (int i = 0; i < ta.octree().stored_brick_count(); ++i)
    for (int t = 0; t < steps; ++t) {
      const std::size_t n = std::size_t(ta.octree().lattice(i).count());
      ca.resize(n), cb.resize(n), ia.resize(n), ib.resize(n);
      a->read_brick(i, t, ca);
      b->read_brick(i, t, cb);
      ASSERT_EQ(ca, cb) << "brick " << i << " step " << t;
      if (!stencil) continue;
      a->read_inside(i, t, ia);
      b->read_inside(i, t, ib);
      ASSERT_EQ(ia, ib) << "stencil of brick " << i << " step " << t;
    }
  for (int i = 0; i < ta.size(); ++i) {
    const tsp::NodeStats& sa = ta.stats(i);
    const tsp::NodeStats& sb = tb.stats(i);
    ASSERT_TRUE(same_bits(sa.mean, sb.mean) && same_bits(sa.std, sb.std) &&
                same_bits(sa.min, sb.min) && same_bits(sa.max, sb.max) &&
                same_bits(sa.spatial_error, sb.spatial_error) &&
                same_bits(sa.temporal_error, sb.temporal_error))
        << "statistics of node " << i;
  }
  const auto la = ta.level_errors(), lb = tb.level_errors();
  ASSERT_EQ(la.size(), lb.size());
  EXPECT_EQ(0, std::memcmp(la.data(), lb.data(), la.size_bytes())) << "level residuals";
  const tsp::TspMetadata &ma = a->metadata(), &mb = b->metadata();
  EXPECT_EQ(ma.histogram, mb.histogram);
  EXPECT_TRUE(same_bits(ma.data_range, mb.data_range));
  EXPECT_TRUE(same_bits(ta.value_range(), tb.value_range()));
  EXPECT_EQ(ma.nonfinite_count, mb.nonfinite_count);
  EXPECT_EQ(ma.origin, mb.origin);
  EXPECT_EQ(ma.spacing, mb.spacing);
  EXPECT_EQ(ma.times, mb.times);
  EXPECT_EQ(ma.build_ranks, 1);
  EXPECT_EQ(mb.build_ranks, ranks);
}

}  // namespace tsptest
