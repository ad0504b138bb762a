#include "tsp/report/image.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "support/paths.h"
#include "support/reader_formula.h"
#include "tsp/core/error.h"

namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;
using tsptest::error_of;

// A minimal PNG encoder written from the PNG specification (signature, IHDR, one IDAT of
// zlib-compressed filter-0 scanlines, IEND), independent of libpng.
void put32(Bytes& b, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) b.push_back(std::uint8_t(v >> s));
}
void chunk(Bytes& out, const char* type, const Bytes& data) {
  put32(out, std::uint32_t(data.size()));
  Bytes td(type, type + 4);
  td.insert(td.end(), data.begin(), data.end());
  out.insert(out.end(), td.begin(), td.end());
  put32(out, std::uint32_t(crc32(0, td.data(), uInt(td.size()))));
}
Bytes encode_png(int w, int h, int bit_depth, int colour_type, const Bytes& raw_rows) {
  Bytes out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  Bytes ihdr;
  put32(ihdr, std::uint32_t(w));
  put32(ihdr, std::uint32_t(h));
  ihdr.insert(ihdr.end(), {std::uint8_t(bit_depth), std::uint8_t(colour_type), 0, 0, 0});
  chunk(out, "IHDR", ihdr);
  uLongf len = compressBound(uLong(raw_rows.size()));
  Bytes z(len);
  EXPECT_EQ(compress(z.data(), &len, raw_rows.data(), uLong(raw_rows.size())), Z_OK);
  z.resize(len);
  chunk(out, "IDAT", z);
  chunk(out, "IEND", {});
  return out;
}
void write_bytes(const fs::path& p, const Bytes& b) {
  std::ofstream(p, std::ios::binary)
      .write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

// An 8-bit grey PNG: grey(x, y) = 10·x + 40·y.
constexpr int kGreyW = 5, kGreyH = 3;
Bytes grey_png() {
  Bytes rows;
  for (int y = 0; y < kGreyH; ++y) {
    rows.push_back(0);  // filter type None
    for (int x = 0; x < kGreyW; ++x) rows.push_back(std::uint8_t(10 * x + 40 * y));
  }
  return encode_png(kGreyW, kGreyH, 8, 0, rows);
}

tsp::Image random_image(int w, int h, unsigned seed) {
  tsp::Image img(w, h);
  std::mt19937 rng(seed);
  for (auto& v : img.rgba) v = std::uint8_t(rng());
  return img;
}

TEST(Image, ConstructsTransparentBlackAndAddressesTopDown) {
  tsp::Image img(3, 2);
  EXPECT_EQ(img.rgba.size(), 24u);
  EXPECT_EQ(img.pixels(), 6);
  for (auto v : img.rgba) EXPECT_EQ(v, 0);
  img.at(2, 1)[3] = 7;
  EXPECT_EQ(img.rgba[4 * (1 * 3 + 2) + 3], 7);
}

TEST(Image, PngRoundTripIsExactForEveryByteIncludingAlpha) {
  const fs::path p = tsptest::temp_dir() / "round.png";
  for (auto [w, h] : {std::pair{1, 1}, {7, 5}, {64, 3}}) {
    const tsp::Image img = random_image(w, h, unsigned(w * 100 + h));
    tsp::write_png(p.string(), img);
    const tsp::Image back = tsp::read_png(p.string());
    EXPECT_EQ(back.width, w);
    EXPECT_EQ(back.height, h);
    EXPECT_EQ(back.rgba, img.rgba) << w << "x" << h;
  }
}

TEST(Image, WrittenFileIsAn8BitRgbaPngWithTheRightHeader) {
  const fs::path p = tsptest::temp_dir() / "hdr.png";
  tsp::write_png(p.string(), tsp::Image(300, 2));
  std::ifstream in(p, std::ios::binary);
  Bytes b((std::istreambuf_iterator<char>(in)), {});
  ASSERT_GT(b.size(), 33u);
  const Bytes sig = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  EXPECT_TRUE(std::equal(sig.begin(), sig.end(), b.begin()));
  EXPECT_EQ(std::string(b.begin() + 12, b.begin() + 16), "IHDR");
  auto be32 = [&](std::size_t o) {
    return std::uint32_t(b[o]) << 24 | std::uint32_t(b[o + 1]) << 16 | b[o + 2] << 8 | b[o + 3];
  };
  EXPECT_EQ(be32(16), 300u);
  EXPECT_EQ(be32(20), 2u);
  EXPECT_EQ(b[24], 8);  // bit depth
  EXPECT_EQ(b[25], 6);  // colour type RGBA
}

TEST(Image, ReadsAGreyPngFromAnIndependentEncoderAsOpaqueRgb) {
  const fs::path p = tsptest::temp_dir() / "grey.png";
  write_bytes(p, grey_png());
  const tsp::Image img = tsp::read_png(p.string());
  ASSERT_EQ(img.width, kGreyW);
  ASSERT_EQ(img.height, kGreyH);
  for (int y = 0; y < kGreyH; ++y)
    for (int x = 0; x < kGreyW; ++x) {
      const std::uint8_t* px = img.at(x, y);
      const int g = 10 * x + 40 * y;
      EXPECT_EQ(px[0], g);
      EXPECT_EQ(px[1], g);
      EXPECT_EQ(px[2], g);
      EXPECT_EQ(px[3], 255);
    }
}

TEST(Image, ReadsAnRgbPngWithoutAlphaAsOpaque) {
  Bytes rows = {0, 1, 2, 3, 250, 251, 252};  // one row, two RGB pixels
  const fs::path p = tsptest::temp_dir() / "rgb.png";
  write_bytes(p, encode_png(2, 1, 8, 2, rows));
  const tsp::Image img = tsp::read_png(p.string());
  EXPECT_EQ(img.rgba, (Bytes{1, 2, 3, 255, 250, 251, 252, 255}));
}

TEST(Image, MissingFileAndDirectoryAreIoErrorsNamingThePath) {
  const fs::path dir = tsptest::temp_dir();
  const std::string missing = (dir / "nope.png").string();
  EXPECT_NE(error_of<tsp::IoError>([&] { tsp::read_png(missing); }).find(missing),
            std::string::npos);
  EXPECT_NE(error_of<tsp::IoError>([&] { tsp::read_png(dir.string()); }).find("directory"),
            std::string::npos);
}

TEST(Image, NonPngEmptyAndTruncatedFilesAreFormatErrorsNamingThePath) {
  const fs::path dir = tsptest::temp_dir();
  const fs::path text = dir / "text.png", empty = dir / "empty.png", cut = dir / "cut.png",
                 bad_crc = dir / "crc.png";
  std::ofstream(text) << "this is not a PNG file at all\n";
  std::ofstream(empty).flush();
  Bytes whole = grey_png();
  write_bytes(cut, Bytes(whole.begin(), whole.end() - 20));  // inside IDAT
  Bytes corrupt = whole;
  corrupt[29] ^= 0xFF;  // IHDR's CRC
  write_bytes(bad_crc, corrupt);
  for (const fs::path& p : {text, empty, cut, bad_crc}) {
    const std::string msg = error_of<tsp::FormatError>([&] { tsp::read_png(p.string()); });
    EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
  }
}

TEST(Image, HugeDeclaredSizeIsRefusedBeforeAllocating) {
  // A valid header declaring 65536 × 65536 pixels (2^32 > kMaxPngPixels) and no real data.
  const fs::path p = tsptest::temp_dir() / "huge.png";
  write_bytes(p, encode_png(65536, 65536, 8, 0, Bytes{0}));
  const std::string msg = error_of<tsp::FormatError>([&] { tsp::read_png(p.string()); });
  EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
}

TEST(Image, WriteErrorsLeaveNoFileBehind) {
  const fs::path dir = tsptest::temp_dir();
  EXPECT_THROW(tsp::write_png((dir / "no_dir" / "x.png").string(), tsp::Image(2, 2)), tsp::IoError);
  EXPECT_THROW(tsp::write_png((dir / "empty.png").string(), tsp::Image(0, 3)), tsp::UsageError);
  EXPECT_THROW(tsp::write_png(dir.string(), tsp::Image(2, 2)), tsp::IoError);
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(Image, RewritingReplacesTheFileAndLeavesNoTemporary) {
  const fs::path dir = tsptest::temp_dir();
  const fs::path p = dir / "again.png";
  tsp::write_png(p.string(), random_image(4, 4, 1));
  const tsp::Image second = random_image(3, 2, 2);
  tsp::write_png(p.string(), second);
  EXPECT_EQ(tsp::read_png(p.string()).rgba, second.rgba);
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
}

}  // namespace
