#include "tsp/source/raw_source.h"

#include <glob.h>

#include <bit>
#include <cassert>
#include <cctype>
#include <climits>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>

#include "tsp/core/error.h"
#include "tsp/core/file_check.h"
#include "tsp/source/natural_order.h"

namespace tsp::io {
namespace {

namespace fs = std::filesystem;

// A parsed printf pattern: prefix, %[0][width]d, suffix ("%%" already turned into '%').
struct IndexPattern {
  std::string prefix, suffix;
  bool zero_pad = false;
  int width = 0;

  std::string format(int i) const {
    std::string digits = std::to_string(i);
    if (int(digits.size()) < width)
      digits.insert(0, std::size_t(width) - digits.size(), zero_pad ? '0' : ' ');
    return prefix + digits + suffix;
  }
};

// Parses the single %d conversion, refusing anything else (the pattern is never handed to
// printf, so a stray %s cannot read memory).
std::optional<IndexPattern> parse_index_pattern(const std::string& p) {
  IndexPattern out;
  bool found = false;
  std::string* part = &out.prefix;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p[i] != '%') {
      *part += p[i];
      continue;
    }
    if (i + 1 < p.size() && p[i + 1] == '%') {
      *part += '%';
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    bool zero = false;
    if (j < p.size() && p[j] == '0') {
      zero = true;
      ++j;
    }
    int width = 0;
    while (j < p.size() && std::isdigit(static_cast<unsigned char>(p[j])) && width < 100)
      width = width * 10 + (p[j++] - '0');
    if (j >= p.size() || p[j] != 'd')
      throw UsageError(p + ": unsupported conversion in the file pattern, expected %d, %0Nd or %%");
    if (found) throw UsageError(p + ": the file pattern has several %d, expected one");
    found = true;
    out.zero_pad = zero;
    out.width = width;
    part = &out.suffix;
    i = j;
  }
  if (!found) return std::nullopt;
  return out;
}

bool file_exists(const std::string& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

int bytes_per_sample(RawType t) {
  switch (t) {
    case RawType::u8:
      return 1;
    case RawType::u16:
      return 2;
    case RawType::f32:
      return 4;
  }
  return 4;
}

const char* type_name(RawType t) {
  switch (t) {
    case RawType::u8:
      return "u8";
    case RawType::u16:
      return "u16";
    case RawType::f32:
      return "f32";
  }
  return "?";
}

class RawSource final : public VolumeSource {
 public:
  RawSource(std::string pattern, std::vector<std::string> files, Dims dims, RawType type,
            bool big_endian)
      : pattern_(std::move(pattern)),
        files_(std::move(files)),
        dims_(dims),
        type_(type),
        big_endian_(big_endian) {}

  Dims dims() const override { return dims_; }
  int steps() const override { return int(files_.size()); }
  std::vector<std::string> files() const override { return files_; }
  std::string describe() const override {
    return pattern_ + " (" + std::to_string(files_.size()) + " raw " + type_name(type_) + " " +
           (big_endian_ ? "big" : "little") + "-endian files of " + to_string(dims_) + ")";
  }

  void read_step(int t, std::span<float> out) override { read_slab(t, 0, dims_.z, out); }
  bool reads_slabs() const override { return true; }
  void read_slab(int t, int z0, int z1, std::span<float> out) override {
    assert(t >= 0 && t < steps() && 0 <= z0 && z0 < z1 && z1 <= dims_.z);
    const std::uint64_t plane = std::uint64_t(dims_.x) * std::uint64_t(dims_.y);
    assert(out.size() == plane * std::uint64_t(z1 - z0));
    const std::string& file = files_[std::size_t(t)];
    const std::uint64_t expected = std::uint64_t(dims_.count()) * bytes_per_sample(type_);
    std::ifstream in(file, std::ios::binary);
    if (!in) throw IoError(file + ": cannot be opened for reading");
    // The whole file's size is checked whichever planes are read.
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0 || std::uint64_t(size) != expected)
      throw FormatError(file + ": holds " + std::to_string(std::max<std::streamoff>(size, 0)) +
                        " bytes, expected " + std::to_string(expected) + " (" + to_string(dims_) +
                        " " + type_name(type_) + ")");
    const std::uint64_t bytes = out.size() * bytes_per_sample(type_);
    buffer_.resize(bytes);
    in.seekg(std::streamoff(plane * std::uint64_t(z0) * bytes_per_sample(type_)));
    in.read(reinterpret_cast<char*>(buffer_.data()), std::streamsize(bytes));
    if (std::uint64_t(in.gcount()) != bytes)
      throw IoError(file + ": read " + std::to_string(in.gcount()) + " of " +
                    std::to_string(bytes) + " bytes at plane " + std::to_string(z0));
    convert(out);
  }

 private:
  void convert(std::span<float> out) const {
    const bool swap = big_endian_ != (std::endian::native == std::endian::big);
    const unsigned char* b = buffer_.data();
    switch (type_) {
      case RawType::u8:
        for (std::size_t i = 0; i < out.size(); ++i) out[i] = float(b[i]);
        break;
      case RawType::u16:
        for (std::size_t i = 0; i < out.size(); ++i) {
          std::uint16_t v;
          std::memcpy(&v, b + 2 * i, 2);
          if (swap) v = std::uint16_t((v >> 8) | (v << 8));
          out[i] = float(v);
        }
        break;
      case RawType::f32:
        for (std::size_t i = 0; i < out.size(); ++i) {
          std::uint32_t v;
          std::memcpy(&v, b + 4 * i, 4);
          if (swap) v = __builtin_bswap32(v);
          out[i] = std::bit_cast<float>(v);
        }
        break;
    }
  }

  std::string pattern_;
  std::vector<std::string> files_;
  Dims dims_;
  RawType type_;
  bool big_endian_;
  std::vector<unsigned char> buffer_;
};

}  // namespace

bool is_file_pattern(const std::string& input) {
  if (input.find_first_of("*?[") != std::string::npos) return true;
  try {
    return parse_index_pattern(input).has_value();
  } catch (const UsageError&) {
    return true;  // a malformed printf pattern is still meant as one; expanding it reports why
  }
}

std::vector<std::string> expand_file_pattern(const std::string& pattern) {
  if (pattern.find('\0') != std::string::npos)
    throw UsageError("a file pattern holds a NUL byte, which no file name can hold");
  std::vector<std::string> files;
  if (auto ip = parse_index_pattern(pattern)) {
    int first = file_exists(ip->format(0)) ? 0 : 1;
    for (int i = first; i < INT32_MAX && file_exists(ip->format(i)); ++i) {
      if (int(files.size()) >= kMaxSteps)
        throw FormatError(pattern + ": matches more than " + std::to_string(kMaxSteps) +
                          " files, the most time steps a series may have");
      files.push_back(ip->format(i));
    }
    if (files.empty())
      throw IoError(pattern + ": no file matches (tried " + ip->format(0) + " and " +
                    ip->format(1) + ")");
    return files;
  }
  if (pattern.find_first_of("*?[") != std::string::npos) {
    glob_t g{};
    int rc = glob(pattern.c_str(), GLOB_NOSORT, nullptr, &g);
    for (std::size_t i = 0; rc == 0 && i < g.gl_pathc; ++i)
      if (file_exists(g.gl_pathv[i])) files.push_back(g.gl_pathv[i]);
    globfree(&g);
    if (files.size() > std::size_t(kMaxSteps))
      throw FormatError(pattern + ": matches " + std::to_string(files.size()) +
                        " files, more than the " + std::to_string(kMaxSteps) +
                        " time steps a series may have");
    if (files.empty()) throw IoError(pattern + ": no file matches the pattern");
    natural_sort(files);
    return files;
  }
  require_regular_file(pattern, "input");
  return {pattern};
}

std::unique_ptr<VolumeSource> open_raw_source(const std::string& input,
                                              const SourceOptions& options) {
  if (!options.raw_dims) throw UsageError(input + ": raw input needs the grid size (--raw-dims X,Y,Z)");
  const Dims d = *options.raw_dims;
  if (d.x <= 0 || d.y <= 0 || d.z <= 0)
    throw UsageError(input + ": raw grid size " + to_string(d) + " must be positive on every axis");
  std::vector<std::string> files = expand_file_pattern(input);
  const std::uintmax_t expected = std::uintmax_t(d.count()) * bytes_per_sample(options.raw_type);
  for (const std::string& f : files) {
    std::error_code ec;
    std::uintmax_t size = fs::file_size(f, ec);
    if (ec) throw IoError(f + ": cannot read the file size (" + ec.message() + ")");
    if (size != expected)
      throw FormatError(f + ": holds " + std::to_string(size) + " bytes, expected " +
                        std::to_string(expected) + " (" + to_string(d) + " " +
                        type_name(options.raw_type) + ")");
  }
  return std::make_unique<RawSource>(input, std::move(files), d, options.raw_type,
                                     options.raw_big_endian);
}

}  // namespace tsp::io
