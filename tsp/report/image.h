// tsp/report: images, image differences and plots for reports and tests; may include core/.
// RGBA8 images and PNG files (libpng). No OpenGL here.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace tsp {

/// An 8-bit RGBA image, top row first, 4 bytes per pixel (R, G, B, A), rows packed.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;

  Image() = default;
  /// A width × height image of transparent black. Asserts on negative sizes.
  Image(int w, int h);
  /// Pointer to the 4 bytes of pixel (x, y), y = 0 at the top.
  std::uint8_t* at(int x, int y) { return rgba.data() + 4 * (std::size_t(y) * width + x); }
  /// Read-only pointer to the 4 bytes of pixel (x, y).
  const std::uint8_t* at(int x, int y) const {
    return rgba.data() + 4 * (std::size_t(y) * width + x);
  }
  /// Number of pixels.
  std::int64_t pixels() const { return std::int64_t(width) * height; }
};

/// Largest image read_png accepts (pixels): 8192 x 8192, the largest `render --size`, so a hostile
/// header cannot ask for more than 256 MiB of RGBA.
inline constexpr std::int64_t kMaxPngPixels = std::int64_t(8192) * 8192;
/// Largest PNG file read_png reads (bytes): more than any 8192 x 8192 RGBA image compresses to.
inline constexpr std::int64_t kMaxPngFileBytes = std::int64_t(512) << 20;

/// Reads a PNG of any colour type and bit depth as 8-bit RGBA (missing alpha = 255; 8-bit sRGB
/// files, which write_png produces, are read exactly). Throws IoError when the file cannot be
/// opened or is not a regular file of at most kMaxPngFileBytes (tsp::read_input_file),
/// FormatError when it is not a PNG, is truncated or corrupt, or holds more than kMaxPngPixels.
Image read_png(const std::string& path);

/// Writes img as an 8-bit RGBA PNG marked sRGB, atomically (temporary file, then rename).
/// Throws UsageError for an empty image, IoError when the file cannot be written.
void write_png(const std::string& path, const Image& img);

}  // namespace tsp
