// A scalar texture's samples kept in RAM beside (or instead of) its GL texture: what the CPU
// ray caster (cpu_caster.h) reads. The layout is the GL texture's — x fastest, one or two 16-bit
// channels per texel (code, stencil 0 or 65535) — so a BrickSlot's offset and scale address both.
#pragma once
#include <algorithm>
#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tspgl {

/// Spare texels after a HostVolume's last one: a SIMD read of a texel and its x neighbour
/// (cpu_batch.h) at the very last texel stays inside the allocation.
inline constexpr std::size_t kHostVolumePad = 4;

/// 16-bit texels of a 3-D texture in RAM (x fastest, `channels` interleaved per texel).
struct HostVolume {
  std::array<int, 3> size{};  ///< texels per axis
  int channels = 1;           ///< 1 (codes) or 2 (codes, stencil)
  std::vector<std::uint16_t> texels;

  /// Resizes to w × h × d texels of `channels` channels, contents zero. Never throws but
  /// std::bad_alloc.
  void allocate(int w, int h, int d, int ch) {
    size = {w, h, d};
    channels = ch;
    texels.assign(std::size_t(w) * std::size_t(h) * std::size_t(d) * std::size_t(ch) + kHostVolumePad,
                  0);
  }
  /// Copies a box of w × h × d texels (x fastest, `channels` interleaved) to texel origin o.
  void write(std::array<int, 3> o, int w, int h, int d, const std::uint16_t* src) {
    assert(o[0] + w <= size[0] && o[1] + h <= size[1] && o[2] + d <= size[2]);
    const std::size_t row = std::size_t(w) * std::size_t(channels);
    for (int z = 0; z < d; ++z)
      for (int y = 0; y < h; ++y) {
        const std::size_t at =
            (std::size_t(o[0]) + std::size_t(size[0]) * (std::size_t(o[1] + y) +
                                                         std::size_t(size[1]) * std::size_t(o[2] + z))) *
            std::size_t(channels);
        const std::uint16_t* from = src + (std::size_t(y) + std::size_t(h) * std::size_t(z)) * row;
        std::copy(from, from + row, texels.begin() + std::ptrdiff_t(at));
      }
  }
  /// Copies a box of `box` texels (all channels) from texel origin `from` to texel origin `to`;
  /// the two boxes must not overlap. Never throws.
  void copy_within(std::array<int, 3> from, std::array<int, 3> to, std::array<int, 3> box) {
    assert(from[0] + box[0] <= size[0] && from[1] + box[1] <= size[1] && from[2] + box[2] <= size[2]);
    assert(to[0] + box[0] <= size[0] && to[1] + box[1] <= size[1] && to[2] + box[2] <= size[2]);
    const std::size_t row = std::size_t(box[0]) * std::size_t(channels);
    auto at = [&](const std::array<int, 3>& o, int y, int z) {
      return (std::size_t(o[0]) +
              std::size_t(size[0]) * (std::size_t(o[1] + y) + std::size_t(size[1]) * std::size_t(o[2] + z))) *
             std::size_t(channels);
    };
    for (int z = 0; z < box[2]; ++z)
      for (int y = 0; y < box[1]; ++y)
        std::copy_n(texels.begin() + std::ptrdiff_t(at(from, y, z)), row,
                    texels.begin() + std::ptrdiff_t(at(to, y, z)));
  }
  /// True when allocated.
  bool empty() const { return texels.empty(); }
};

}  // namespace tspgl
