#include "tsp/source/vtk/vtk_xml.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <climits>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <type_traits>

#include "tsp/core/error.h"

namespace tsp::io::vtkxml {
namespace {

// 0..63 for base64 alphabet characters, kBase64Space for whitespace, -1 otherwise (a table:
// std::isspace per character is a library call, and base64 runs to hundreds of megabytes).
constexpr int kBase64Space = -2;
constexpr std::array<int, 256> make_base64_table() {
  std::array<int, 256> t{};
  for (int& v : t) v = -1;
  for (char c : {' ', '\t', '\n', '\v', '\f', '\r'}) t[static_cast<unsigned char>(c)] = kBase64Space;
  const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  for (int i = 0; i < 64; ++i) t[static_cast<unsigned char>(alphabet[i])] = i;
  return t;
}
constexpr std::array<int, 256> kBase64 = make_base64_table();

std::uint64_t read_word(const unsigned char* p, int size, bool big_endian) {
  std::uint64_t v = 0;
  for (int i = 0; i < size; ++i) {
    int shift = 8 * (big_endian ? size - 1 - i : i);
    v |= std::uint64_t(p[i]) << shift;
  }
  return v;
}

float saturate(double v) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (v > kMax) return std::numeric_limits<float>::infinity();
  if (v < -kMax) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(v);
}

// Element i of type T in file byte order (swap: the other order than this machine's).
template <typename T>
T load(std::span<const unsigned char> bytes, std::size_t i, bool swap) {
  unsigned char tmp[sizeof(T)];
  std::memcpy(tmp, bytes.data() + i * sizeof(T), sizeof(T));
  if (swap)
    for (std::size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(tmp[k], tmp[sizeof(T) - 1 - k]);
  T v;
  std::memcpy(&v, tmp, sizeof(T));
  return v;
}

template <typename T>
void convert_int(std::span<const unsigned char> bytes, bool swap, std::span<std::int64_t> out,
                 const std::string& where) {
  for (std::size_t i = 0; i < out.size(); ++i) {
    const T v = load<T>(bytes, i, swap);
    if constexpr (std::is_same_v<T, std::uint64_t>) {
      if (v > std::uint64_t(std::numeric_limits<std::int64_t>::max()))
        throw FormatError(where + ": value " + std::to_string(v) + " at index " +
                          std::to_string(i) + " exceeds the 64-bit signed range");
    }
    out[i] = static_cast<std::int64_t>(v);
  }
}

template <typename T>
void convert_typed(std::span<const unsigned char> bytes, bool swap, std::span<float> out) {
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = saturate(static_cast<double>(load<T>(bytes, i, swap)));
}

// Calls f.template operator()<T>() with the C++ type of t.
template <typename F>
void dispatch(ElemType t, F&& f) {
  switch (t) {
    case ElemType::i8:
      return f.template operator()<std::int8_t>();
    case ElemType::u8:
      return f.template operator()<std::uint8_t>();
    case ElemType::i16:
      return f.template operator()<std::int16_t>();
    case ElemType::u16:
      return f.template operator()<std::uint16_t>();
    case ElemType::i32:
      return f.template operator()<std::int32_t>();
    case ElemType::u32:
      return f.template operator()<std::uint32_t>();
    case ElemType::i64:
      return f.template operator()<std::int64_t>();
    case ElemType::u64:
      return f.template operator()<std::uint64_t>();
    case ElemType::f32:
      return f.template operator()<float>();
    case ElemType::f64:
      return f.template operator()<double>();
  }
}

}  // namespace

ElemType parse_elem_type(const std::string& name, const std::string& where) {
  static const std::pair<const char*, ElemType> kNames[] = {
      {"Int8", ElemType::i8},     {"UInt8", ElemType::u8},   {"Int16", ElemType::i16},
      {"UInt16", ElemType::u16},  {"Int32", ElemType::i32},  {"UInt32", ElemType::u32},
      {"Int64", ElemType::i64},   {"UInt64", ElemType::u64}, {"Float32", ElemType::f32},
      {"Float64", ElemType::f64}, {"Char", ElemType::i8},    {"UnsignedChar", ElemType::u8}};
  for (const auto& [n, t] : kNames)
    if (name == n) return t;
  throw FormatError(where + ": DataArray type \"" + name +
                    "\" is not supported, expected Int8…UInt64, Float32 or Float64");
}

int elem_size(ElemType t) {
  switch (t) {
    case ElemType::i8:
    case ElemType::u8:
      return 1;
    case ElemType::i16:
    case ElemType::u16:
      return 2;
    case ElemType::i32:
    case ElemType::u32:
    case ElemType::f32:
      return 4;
    case ElemType::i64:
    case ElemType::u64:
    case ElemType::f64:
      return 8;
  }
  return 1;
}

std::vector<unsigned char> base64_decode(std::string_view text, const std::string& where) {
  std::vector<unsigned char> out;
  out.reserve(text.size() / 4 * 3);
  int quad[4];
  int n = 0, pad = 0;
  auto flush = [&] {
    out.push_back(static_cast<unsigned char>((quad[0] << 2) | (quad[1] >> 4)));
    if (pad < 2) out.push_back(static_cast<unsigned char>(((quad[1] & 15) << 4) | (quad[2] >> 2)));
    if (pad < 1) out.push_back(static_cast<unsigned char>(((quad[2] & 3) << 6) | quad[3]));
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    unsigned char c = static_cast<unsigned char>(text[i]);
    if (kBase64[c] == kBase64Space) continue;
    if (c == '=') {
      if (n < 2)
        throw FormatError(where + ": malformed base64 data ('=' at character " + std::to_string(i) +
                          ")");
      quad[n++] = 0;
      ++pad;
    } else {
      if (kBase64[c] < 0 || pad > 0)
        throw FormatError(where + ": malformed base64 data (character " + std::to_string(i) +
                          " is '" + std::string(1, char(c)) + "')");
      quad[n++] = kBase64[c];
    }
    if (n == 4) {
      flush();
      n = 0;
      pad = 0;
    }
  }
  if (n != 0) throw FormatError(where + ": base64 data ends in the middle of a group");
  return out;
}

std::vector<unsigned char> unpack_binary(std::span<const unsigned char> bytes,
                                         const BinaryLayout& layout, std::uint64_t expected_bytes,
                                         const std::string& where, std::uint64_t max_ratio) {
  const int ws = layout.header64 ? 8 : 4;
  auto word = [&](std::uint64_t index) -> std::uint64_t {
    if (index >= bytes.size() / ws)
      throw FormatError(where + ": binary data truncated inside its header (" +
                        std::to_string(bytes.size()) + " bytes available)");
    return read_word(bytes.data() + index * ws, ws, layout.big_endian);
  };
  if (!layout.zlib) {
    std::uint64_t n = word(0);
    if (n != expected_bytes)
      throw FormatError(where + ": binary header says " + std::to_string(n) + " bytes, expected " +
                        std::to_string(expected_bytes));
    if (bytes.size() - ws < n)
      throw FormatError(where + ": binary data truncated: " + std::to_string(bytes.size() - ws) +
                        " of " + std::to_string(n) + " bytes present");
    return std::vector<unsigned char>(bytes.begin() + ws, bytes.begin() + ws + std::ptrdiff_t(n));
  }
  const std::uint64_t blocks = word(0), block_size = word(1), last_size = word(2);
  const std::uint64_t last = last_size ? last_size : block_size;
  // Every product and sum of header values is checked: a header may describe sizes that wrap
  // around to the expected total.
  std::uint64_t total = 0;
  bool ok = true;
  if (blocks) {
    ok = block_size > 0 && last <= block_size &&
         !__builtin_mul_overflow(blocks - 1, block_size, &total) &&
         !__builtin_add_overflow(total, last, &total);
  }
  if (ok && total > kMaxInflateRatio * std::uint64_t(bytes.size()) + kMaxInflateRatio) ok = false;
  if (!ok || total != expected_bytes)
    throw FormatError(where + ": zlib header describes " + std::to_string(blocks) + " blocks of " +
                      std::to_string(block_size) + " bytes (last " + std::to_string(last) +
                      "), expected " + std::to_string(expected_bytes) + " bytes in all");
  // The block-size table must lie inside the data (3 + blocks words).
  if (blocks > bytes.size() / ws - 3 || bytes.size() / ws < 3)
    throw FormatError(where + ": zlib header lists " + std::to_string(blocks) +
                      " blocks but the data holds only " + std::to_string(bytes.size()) + " bytes");
  // What the array stores: its header, table and compressed blocks (a block that runs past the
  // data is reported below; the sum saturates at the data's size).
  std::uint64_t stored = (3 + blocks) * ws;
  for (std::uint64_t b = 0; b < blocks; ++b)
    stored = std::min<std::uint64_t>(stored + std::min<std::uint64_t>(word(3 + b), bytes.size()),
                                     bytes.size());
  std::uint64_t allowed = 0;
  if (!__builtin_mul_overflow(max_ratio, stored, &allowed) && total > allowed + max_ratio)
    throw FormatError(where + ": expected " + std::to_string(expected_bytes) +
                      " bytes of data, found " + std::to_string(stored) +
                      " bytes of zlib blocks to inflate them from (" +
                      std::to_string(total / std::max<std::uint64_t>(stored, 1)) +
                      ":1, more than the " + std::to_string(max_ratio) +
                      ":1 accepted here); refused before decoding");
  std::vector<unsigned char> out(total);
  std::uint64_t src = (3 + blocks) * ws;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const std::uint64_t csize = word(3 + b);
    const std::uint64_t usize = b + 1 == blocks ? last : block_size;
    const std::uint64_t dst = b * block_size;  // < total: no overflow
    if (csize > bytes.size() - src)
      throw FormatError(where + ": zlib block " + std::to_string(b) + " truncated (needs " +
                        std::to_string(csize) + " bytes, " + std::to_string(bytes.size() - src) +
                        " present)");
    if (usize > out.size() - dst)
      throw FormatError(where + ": zlib block " + std::to_string(b) + " overruns the array");
    uLongf dest_len = static_cast<uLongf>(usize);
    int rc = uncompress(out.data() + dst, &dest_len, bytes.data() + src,
                        static_cast<uLong>(csize));
    if (rc != Z_OK || dest_len != usize)
      throw FormatError(where + ": zlib block " + std::to_string(b) + " does not inflate to " +
                        std::to_string(usize) + " bytes (zlib error " + std::to_string(rc) + ")");
    src += csize;
  }
  return out;
}

void convert_to_float(std::span<const unsigned char> bytes, ElemType t, bool big_endian,
                      std::span<float> out) {
  const bool swap = big_endian != (std::endian::native == std::endian::big);
  dispatch(t, [&]<typename T>() { convert_typed<T>(bytes, swap, out); });
}

void convert_to_int64(std::span<const unsigned char> bytes, ElemType t, bool big_endian,
                      std::span<std::int64_t> out, const std::string& where) {
  if (t == ElemType::f32 || t == ElemType::f64)
    throw FormatError(where + ": floating-point data where integers are expected");
  const bool swap = big_endian != (std::endian::native == std::endian::big);
  dispatch(t, [&]<typename T>() {
    if constexpr (std::is_integral_v<T>) convert_int<T>(bytes, swap, out, where);
  });
}

void parse_ascii(std::string_view text, std::span<float> out, const std::string& where) {
  std::size_t count = 0, i = 0;
  const char* base = text.data();
  while (true) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    if (i >= text.size()) break;
    std::size_t end = i;
    while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end]))) ++end;
    double v = 0;
    auto [ptr, ec] = std::from_chars(base + i, base + end, v);
    if (ec != std::errc() || ptr != base + end)
      throw FormatError(where + ": ascii value \"" + std::string(text.substr(i, end - i)) +
                        "\" is not a number");
    if (count < out.size()) out[count] = saturate(v);
    ++count;
    i = end;
  }
  if (count != out.size())
    throw FormatError(where + ": ascii data holds " + std::to_string(count) + " values, expected " +
                      std::to_string(out.size()));
}

void parse_extent(const char* text, long long out[6], const std::string& where, const char* what) {
  std::istringstream in(text ? text : "");
  for (int i = 0; i < 6; ++i)
    if (!(in >> out[i]))
      throw FormatError(where + ": " + what + " \"" + (text ? text : "") + "\" is not 6 integers");
  std::string rest;
  if (in >> rest) throw FormatError(where + ": " + what + " has more than 6 values");
  for (int i = 0; i < 6; ++i)
    if (out[i] < INT32_MIN || out[i] > INT32_MAX)
      throw FormatError(where + ": " + what + " value " + std::to_string(out[i]) +
                        " is outside the 32-bit range");
  for (int a = 0; a < 3; ++a)
    if (out[2 * a + 1] < out[2 * a])
      throw FormatError(where + ": " + what + " axis " + std::to_string(a) + " is [" +
                        std::to_string(out[2 * a]) + ", " + std::to_string(out[2 * a + 1]) +
                        "], expected lo <= hi");
}


}  // namespace tsp::io::vtkxml
