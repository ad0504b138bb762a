#include "tsp/report/image.h"

#include <png.h>

#include <cassert>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "tsp/core/error.h"
#include "tsp/core/input_file.h"
#include "tsp/core/temp_output.h"

namespace tsp {

namespace {

constexpr int kChannels = 4;

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

// libpng's simplified API reports errors through png_image.message instead of longjmp, so no
// C++ object is ever skipped by a jump; this guard releases its state on every path.
struct PngImage {
  png_image img;
  PngImage() {
    std::memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
  }
  ~PngImage() { png_image_free(&img); }
  PngImage(const PngImage&) = delete;
  PngImage& operator=(const PngImage&) = delete;
};

}  // namespace

Image::Image(int w, int h) : width(w), height(h) {
  assert(w >= 0 && h >= 0);
  rgba.assign(std::size_t(w) * std::size_t(h) * kChannels, 0);
}

Image read_png(const std::string& path) {
  const std::string bytes = read_input_file(path, "PNG image", kMaxPngFileBytes);
  PngImage p;
  if (!png_image_begin_read_from_memory(&p.img, bytes.data(), bytes.size()))
    throw FormatError(path + ": not a readable PNG file (libpng: " + p.img.message + ")");
  // The decoded size, checked before anything is allocated for it.
  const std::int64_t pixels = std::int64_t(p.img.width) * p.img.height;
  if (pixels > kMaxPngPixels)
    throw FormatError(path + ": PNG of " + std::to_string(p.img.width) + "x" +
                      std::to_string(p.img.height) + " pixels, expected at most " +
                      std::to_string(kMaxPngPixels) + " pixels (8192x8192)");
  p.img.format = PNG_FORMAT_RGBA;
  Image out(int(p.img.width), int(p.img.height));
  if (!png_image_finish_read(&p.img, nullptr, out.rgba.data(), 0, nullptr))
    throw FormatError(path + ": truncated or corrupt PNG data (libpng: " + p.img.message + ")");
  return out;
}

void write_png(const std::string& path, const Image& img) {
  if (img.width <= 0 || img.height <= 0)
    throw UsageError(path + ": cannot write an empty " + std::to_string(img.width) + "x" +
                     std::to_string(img.height) + " image");
  assert(img.rgba.size() == std::size_t(img.pixels()) * kChannels);
  TempOutput out(path);
  {
    FilePtr f(std::fopen(out.tmp().c_str(), "wb"));
    if (!f) throw IoError(path + ": cannot write (" + std::strerror(errno) + ")");
    PngImage p;
    p.img.width = png_uint_32(img.width);
    p.img.height = png_uint_32(img.height);
    p.img.format = PNG_FORMAT_RGBA;
    if (!png_image_write_to_stdio(&p.img, f.get(), 0, img.rgba.data(), 0, nullptr))
      throw IoError(path + ": cannot write the PNG (libpng: " + p.img.message + ")");
    std::FILE* raw = f.release();
    if (std::fflush(raw) != 0 || std::ferror(raw) != 0) {
      const int err = errno;
      std::fclose(raw);
      throw IoError(path + ": cannot write (" + std::strerror(err) + ")");
    }
    if (std::fclose(raw) != 0)
      throw IoError(path + ": cannot write (" + std::strerror(errno) + ")");
  }
  out.commit();
}

}  // namespace tsp
