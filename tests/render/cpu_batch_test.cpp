// The CPU caster's SIMD batches (render/cpu_batch.h) on every target Highway compiled and this
// CPU runs (AVX-512, AVX2, SSE4, SSSE3 and the scalar fallback): each lane of sample_batch and
// shade_batch against the scalar Sampler (cpu_sample.h) at random positions inside a brick, on
// its faces, beyond them (the neighbour brick's taps, and one-sided taps where there is none)
// and at the texture's last texels.
#include <gtest/gtest.h>

#include <hwy/targets.h>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "render/cpu_batch.h"

namespace tspgl::detail {
namespace {

constexpr int kEntries = 64;
constexpr float kTolerance = 2e-5f;  // FMA against separate multiply and add, per channel

struct BatchScene {
  HostVolume volume;
  std::vector<float> row;
  CastScene scene;
  BrickView brick;

  BatchScene() {
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> code(0, 65535);
    // Two 8-texel bricks side by side along x in a 17 × 9 × 9 texture (a spare texel a side).
    volume.allocate(17, 9, 9, 1);
    for (std::size_t i = 0; i + kHostVolumePad < volume.texels.size(); ++i)
      volume.texels[i] = std::uint16_t(code(rng));
    std::uniform_real_distribution<float> unit(0.f, 1.f);
    row.resize(4 * kEntries);
    for (int e = 0; e < kEntries; ++e) {
      const float a = e % 5 == 0 ? 0.f : unit(rng);  // some transparent entries
      for (int c = 0; c < 3; ++c) row[std::size_t(4 * e + c)] = unit(rng) * a;
      row[std::size_t(4 * e + 3)] = a;
    }
    scene.volume = &volume;
    scene.shade = true;
    scene.phong = {0.3f, 0.6f, 0.4f, 10.f};
    scene.light_dir = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
    scene.inv_voxel = {1.f, 0.5f, 1.f};
    scene.tf.entries = kEntries;
    scene.tf.point = row.data();
    scene.tf.scale = 1.1f;
    scene.tf.offset = -0.05f;
    // The first brick: texels 0..8 in x, its upper x face beside a level-0 brick 8 texels on.
    brick.lo = glm::vec3(0.f);
    brick.hi = glm::vec3(8.f);
    brick.k = glm::vec3(0.f);
    brick.beyond_hi[0] = glm::vec4(0.f, 0.f, 0.f, 1.f);  // same texture, no shift: read on
  }
};

// Positions: deep inside, inside, on faces, a texel beyond them, and at the texture's far corner.
std::vector<glm::vec3> positions() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> in(0.f, 8.f), edge(-0.6f, 0.6f), deep(1.5f, 6.5f);
  std::vector<glm::vec3> p;
  // First, batches whose taps all lie inside (the 32-texel stencil's path).
  for (int i = 0; i < 48; ++i) p.push_back({deep(rng), deep(rng), deep(rng)});
  for (int i = 0; i < 200; ++i) p.push_back({in(rng), in(rng), in(rng)});
  for (int i = 0; i < 100; ++i) p.push_back({8.f + edge(rng), in(rng), in(rng)});
  for (int i = 0; i < 100; ++i) p.push_back({in(rng), edge(rng), 8.f + edge(rng)});
  p.push_back({8.f, 8.f, 8.f});
  p.push_back({0.f, 0.f, 0.f});
  return p;
}

void expect_near(glm::vec4 want, float r, float g, float b, float a, const std::string& what) {
  EXPECT_NEAR(r, want.r, kTolerance) << what;
  EXPECT_NEAR(g, want.g, kTolerance) << what;
  EXPECT_NEAR(b, want.b, kTolerance) << what;
  EXPECT_NEAR(a, want.a, kTolerance) << what;
}

// Every lane of sample_batch (unlit and lit) and shade_batch against the scalar sampler, in
// batches of every length up to kMaxBatch.
void check_target(const BatchScene& bs, const std::string& target) {
  const Sampler smp(bs.scene);
  ASSERT_TRUE(batch_ready(smp));
  CastScene unlit_scene = bs.scene;
  unlit_scene.shade = false;
  const Sampler unlit(unlit_scene);
  const std::vector<glm::vec3> pts = positions();
  std::size_t at = 0;
  for (int n = 1; at < pts.size(); n = n % kMaxBatch + 1) {
    const int m = int(std::min<std::size_t>(std::size_t(n), pts.size() - at));
    Positions pos;
    for (int i = 0; i < m; ++i) {
      pos.x[i] = pts[at + std::size_t(i)].x;
      pos.y[i] = pts[at + std::size_t(i)].y;
      pos.z[i] = pts[at + std::size_t(i)].z;
    }
    Colours plain, lit, shaded;
    sample_batch(unlit, bs.brick, bs.row.data(), pos, m, false, plain);
    sample_batch(smp, bs.brick, bs.row.data(), pos, m, true, lit);
    shaded = plain;
    shade_batch(smp, bs.brick, pos, m, shaded);
    for (int i = 0; i < m; ++i) {
      const glm::vec3 p(pos.x[i], pos.y[i], pos.z[i]);
      const std::string what = target + " at (" + std::to_string(p.x) + ", " + std::to_string(p.y) +
                               ", " + std::to_string(p.z) + ")";
      expect_near(unlit.point(p, bs.brick, bs.row.data()), plain.r[i], plain.g[i], plain.b[i],
                  plain.a[i], what + " unlit");
      const glm::vec4 want = smp.point(p, bs.brick, bs.row.data());
      expect_near(want, lit.r[i], lit.g[i], lit.b[i], lit.a[i], what + " lit");
      expect_near(want, shaded.r[i], shaded.g[i], shaded.b[i], shaded.a[i], what + " shaded");
    }
    at += std::size_t(m);
  }
}

TEST(CpuBatch, EveryTargetMatchesTheScalarSampler) {
  const BatchScene bs;
  int tested = 0;
  for (std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    std::printf("target %s\n", hwy::TargetName(target));
    check_target(bs, hwy::TargetName(target));
    ++tested;
  }
  hwy::SetSupportedTargetsForTest(0);  // back to what the CPU has
  // At least the scalar fallback and one SIMD target (x86-64 always has SSSE3 or better).
  EXPECT_GE(tested, 2);
}

// cut_batch against cut_sample on every target: opacities from 0 (unchanged) through 1 (stays
// 1), fractions of a segment (k < 1, a run's cut ends) and a level brick's slabs (k = 2, 4, 8).
TEST(CpuBatch, CutBatchMatchesCutSampleOnEveryTarget) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  const float ks[] = {0.01f, 0.3f, 0.999f, 1.f, 2.f, 3.5f, 4.f, 8.f};
  Colours in;
  alignas(64) float k[kMaxBatch];
  for (int i = 0; i < kMaxBatch; ++i) {
    const float a = i == 0 ? 0.f : i == 1 ? 1.f : unit(rng);
    in.a[i] = a;
    in.r[i] = unit(rng) * a;
    in.g[i] = unit(rng) * a;
    in.b[i] = unit(rng) * a;
    k[i] = ks[i % 8];
  }
  int tested = 0;
  for (std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    for (int n : {kMaxBatch, 5}) {  // whole vectors, and a tail
      Colours c = in;
      cut_batch(k, n, c);
      for (int i = 0; i < kMaxBatch; ++i) {
        const glm::vec4 s(in.r[i], in.g[i], in.b[i], in.a[i]);
        const glm::vec4 want = i < n ? cut_sample(s, k[i]) : s;  // lanes past n untouched
        expect_near(want, c.r[i], c.g[i], c.b[i], c.a[i],
                    std::string(hwy::TargetName(target)) + " lane " + std::to_string(i) +
                        " k " + std::to_string(k[i]));
      }
    }
    ++tested;
  }
  hwy::SetSupportedTargetsForTest(0);
  EXPECT_GE(tested, 2);
}

}  // namespace
}  // namespace tspgl::detail
