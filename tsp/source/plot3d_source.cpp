#include "tsp/source/plot3d_source.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "tsp/core/error.h"
#include "tsp/core/file_check.h"
#include "tsp/source/raw_source.h"
#include "tsp/source/series_list.h"
#include "tsp/source/vts_file.h"

namespace tsp {
namespace {

namespace fs = std::filesystem;

constexpr std::int64_t kMaxBlocks = 1 << 16;         // blocks one file may declare
constexpr std::int64_t kMaxBlockEdge = INT32_MAX;    // points on one axis of a block
constexpr double kGamma = 1.4;                       // VTK's PLOT3D reader's default γ
constexpr int kRecordMarker = 4;                     // bytes of a Fortran record marker
constexpr int kSolutionValues = 5;                   // ρ, ρu, ρv, ρw, ρe per point

using BlockDims = std::array<std::int64_t, 3>;

std::int64_t points_of(const BlockDims& d) { return d[0] * d[1] * d[2]; }

// One binary file, read by offset; every read is checked against its size.
class BinaryFile {
 public:
  explicit BinaryFile(const std::string& path) : path_(path) {
    require_regular_file(path, "PLOT3D file");
    in_.open(path, std::ios::binary);
    if (!in_) throw IoError(path + ": cannot open");
    std::error_code ec;
    size_ = fs::file_size(path, ec);
    if (ec) throw IoError(path + ": cannot read its size: " + ec.message());
  }
  const std::string& path() const { return path_; }
  std::uint64_t size() const { return size_; }
  bool has(std::uint64_t offset, std::uint64_t n) const { return offset <= size_ && n <= size_ - offset; }
  void read(std::uint64_t offset, void* out, std::uint64_t n) {
    if (!has(offset, n))
      throw FormatError(path_ + ": truncated at byte " + std::to_string(offset));
    in_.seekg(std::streamoff(offset));
    in_.read(static_cast<char*>(out), std::streamsize(n));
    if (!in_) throw IoError(path_ + ": read failed at byte " + std::to_string(offset));
  }

 private:
  std::string path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
};

// How a file is laid out: byte order, record markers, the block header, precision, IBLANK.
struct Layout {
  bool big = false, records = false, multi = false, iblank = false;
  int precision = 4;
  std::vector<BlockDims> blocks;
  std::uint64_t data = 0;  // first byte after the header
  std::string text() const {
    return std::to_string(blocks.size()) + " block(s), " +
           (precision == 4 ? "single" : "double") + " precision, " +
           (big ? "big" : "little") + "-endian" + (records ? ", Fortran records" : "") +
           (iblank ? ", IBLANK" : "");
  }
};

std::int32_t int_at(const unsigned char* p, bool big) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  if (big != (std::endian::native == std::endian::big)) v = __builtin_bswap32(v);
  return std::int32_t(v);
}

// Reads the block count and sizes under one guess of byte order, records and block header;
// false when the bytes do not fit that guess.
bool read_header(BinaryFile& f, bool big, bool records, bool multi, Layout& out) {
  std::uint64_t pos = 0;
  unsigned char b[4];
  const auto next = [&](std::int32_t& v) {
    if (!f.has(pos, 4)) return false;
    f.read(pos, b, 4);
    pos += 4;
    v = int_at(b, big);
    return true;
  };
  std::int32_t marker = 0, nb = 1;
  if (multi) {
    if (records && (!next(marker) || marker != 4)) return false;
    if (!next(nb)) return false;
    if (records && (!next(marker) || marker != 4)) return false;
  }
  if (nb < 1 || nb > kMaxBlocks) return false;
  if (records && (!next(marker) || std::int64_t(marker) != 12 * std::int64_t(nb))) return false;
  if (!f.has(pos, 12 * std::uint64_t(nb))) return false;
  std::vector<unsigned char> dims(12 * std::size_t(nb));
  f.read(pos, dims.data(), dims.size());
  pos += dims.size();
  out.blocks.clear();
  for (std::int32_t k = 0; k < nb; ++k) {
    BlockDims d;
    for (int a = 0; a < 3; ++a) {
      d[std::size_t(a)] = int_at(dims.data() + 12 * k + 4 * a, big);
      if (d[std::size_t(a)] < 1 || d[std::size_t(a)] > kMaxBlockEdge) return false;
    }
    // Every point takes at least 4 bytes of the file: a block declaring more cannot fit (and
    // the products of its sizes stay far from overflow).
    if (double(d[0]) * double(d[1]) * double(d[2]) > double(f.size())) return false;
    out.blocks.push_back(d);
  }
  if (records && (!next(marker) || std::int64_t(marker) != 12 * std::int64_t(nb))) return false;
  out.big = big;
  out.records = records;
  out.multi = multi;
  out.data = pos;
  return true;
}

// Bytes of one block's data record (without markers).
std::uint64_t grid_block_bytes(const Layout& l, const BlockDims& d) {
  return std::uint64_t(points_of(d)) * (3 * std::uint64_t(l.precision) + (l.iblank ? 4 : 0));
}
std::uint64_t q_block_bytes(const Layout& l, const BlockDims& d) {
  return std::uint64_t(l.precision) * (4 + kSolutionValues * std::uint64_t(points_of(d)));
}

// Finds the layout whose total size is the file's; solution: a .q file, else a grid.
Layout detect(BinaryFile& f, bool solution) {
  for (bool big : {false, true})
    for (bool records : {true, false})
      for (bool multi : {false, true}) {
        Layout l;
        if (!read_header(f, big, records, multi, l)) continue;
        for (int precision : {4, 8})
          for (bool iblank : solution ? std::vector<bool>{false} : std::vector<bool>{false, true}) {
            l.precision = precision;
            l.iblank = iblank;
            long double total = l.data;  // long double: sums of huge declared sizes never wrap
            for (const BlockDims& d : l.blocks)
              total += (long double)(solution ? q_block_bytes(l, d) : grid_block_bytes(l, d)) +
                       (records ? (solution ? 4 : 2) * kRecordMarker : 0);
            if (total == (long double)f.size()) return l;
          }
      }
  throw FormatError(f.path() + ": " + std::to_string(f.size()) +
                    " bytes fit no binary 3-D PLOT3D " + (solution ? "solution (.q)" : "grid (.xyz)") +
                    " layout (tried both byte orders, with and without Fortran record markers "
                    "and a block count, single and double precision" +
                    (solution ? "" : ", with and without IBLANK") + "); ASCII and 2-D files are "
                    "not read");
}

// n reals from offset, converted to double.
std::vector<double> reals(BinaryFile& f, const Layout& l, std::uint64_t offset, std::int64_t n) {
  std::vector<unsigned char> bytes(std::size_t(n) * std::size_t(l.precision));
  f.read(offset, bytes.data(), bytes.size());
  std::vector<double> out(static_cast<std::size_t>(n));
  const bool swap = l.big != (std::endian::native == std::endian::big);
  for (std::int64_t i = 0; i < n; ++i) {
    const unsigned char* p = bytes.data() + std::size_t(i) * std::size_t(l.precision);
    if (l.precision == 4) {
      std::uint32_t u;
      std::memcpy(&u, p, 4);
      if (swap) u = __builtin_bswap32(u);
      out[std::size_t(i)] = double(std::bit_cast<float>(u));
    } else {
      std::uint64_t u;
      std::memcpy(&u, p, 8);
      if (swap) u = __builtin_bswap64(u);
      out[std::size_t(i)] = std::bit_cast<double>(u);
    }
  }
  return out;
}

// The grid: every block's points and hexahedra (cells touching a blanked point dropped).
Mesh read_grid(const std::string& path, std::vector<BlockDims>& blocks) {
  BinaryFile f(path);
  const Layout l = detect(f, false);
  Mesh m;
  m.offsets.push_back(0);
  std::uint64_t pos = l.data;
  for (std::size_t b = 0; b < l.blocks.size(); ++b) {
    const BlockDims& d = l.blocks[b];
    const std::int64_t n = points_of(d);
    if (l.records) pos += kRecordMarker;
    std::array<std::vector<double>, 3> xyz;
    for (int a = 0; a < 3; ++a) {
      xyz[std::size_t(a)] = reals(f, l, pos, n);
      pos += std::uint64_t(n) * std::uint64_t(l.precision);
    }
    std::vector<std::int32_t> blank;
    if (l.iblank) {
      std::vector<unsigned char> bytes(std::size_t(n) * 4);
      f.read(pos, bytes.data(), bytes.size());
      pos += bytes.size();
      blank.resize(std::size_t(n));
      for (std::int64_t i = 0; i < n; ++i) blank[std::size_t(i)] = int_at(bytes.data() + 4 * i, l.big);
    }
    if (l.records) pos += kRecordMarker;
    if (d[0] < 2 || d[1] < 2 || d[2] < 2)
      throw FormatError(path + ": block " + std::to_string(b) + " is " + std::to_string(d[0]) +
                        " x " + std::to_string(d[1]) + " x " + std::to_string(d[2]) +
                        " points, expected at least 2 on every axis (a volume)");
    const std::int64_t base = m.point_count();
    for (std::int64_t i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) m.points.push_back(xyz[std::size_t(a)][std::size_t(i)]);
    const std::size_t first_cell = m.types.size();
    const std::int64_t n3[3] = {d[0], d[1], d[2]};
    io::append_structured_hexahedra(m, n3, base);
    if (!blank.empty()) {  // keep only cells whose 8 points are all unblanked
      Mesh kept;
      kept.offsets.assign(m.offsets.begin(), m.offsets.begin() + std::ptrdiff_t(first_cell) + 1);
      kept.connectivity.assign(m.connectivity.begin(),
                               m.connectivity.begin() + m.offsets[first_cell]);
      kept.types.assign(m.types.begin(), m.types.begin() + std::ptrdiff_t(first_cell));
      for (std::size_t c = first_cell; c < m.types.size(); ++c) {
        bool visible = true;
        for (std::int64_t k = m.offsets[c]; k < m.offsets[c + 1]; ++k)
          visible = visible && blank[std::size_t(m.connectivity[std::size_t(k)] - base)] != 0;
        if (!visible) continue;
        kept.connectivity.insert(kept.connectivity.end(), m.connectivity.begin() + m.offsets[c],
                                 m.connectivity.begin() + m.offsets[c + 1]);
        kept.offsets.push_back(std::int64_t(kept.connectivity.size()));
        kept.types.push_back(m.types[c]);
      }
      m.offsets = std::move(kept.offsets);
      m.connectivity = std::move(kept.connectivity);
      m.types = std::move(kept.types);
    }
  }
  blocks = l.blocks;
  return m;
}

// One solution: the five values per point of every block, and the header's time.
struct Solution {
  std::array<std::vector<double>, kSolutionValues> q;
  double time = 0;
};

Solution read_solution(const std::string& path, const std::vector<BlockDims>& grid_blocks,
                       const std::string& grid) {
  BinaryFile f(path);
  const Layout l = detect(f, true);
  if (l.blocks != grid_blocks) {
    const auto text = [](const std::vector<BlockDims>& bs) {
      std::string s;
      for (const BlockDims& d : bs)
        s += (s.empty() ? "" : ", ") + std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" +
             std::to_string(d[2]);
      return s;
    };
    throw FormatError(path + ": blocks " + text(l.blocks) + ", but the grid " + grid + " has " +
                      text(grid_blocks));
  }
  Solution s;
  std::uint64_t pos = l.data;
  for (std::size_t b = 0; b < l.blocks.size(); ++b) {
    const std::int64_t n = points_of(l.blocks[b]);
    if (l.records) pos += kRecordMarker;
    const std::vector<double> header = reals(f, l, pos, 4);  // Mach, α, Re, time
    if (b == 0) s.time = header[3];
    pos += 4 * std::uint64_t(l.precision);
    if (l.records) pos += 2 * kRecordMarker;
    for (int v = 0; v < kSolutionValues; ++v) {
      const std::vector<double> r = reals(f, l, pos, n);
      s.q[std::size_t(v)].insert(s.q[std::size_t(v)].end(), r.begin(), r.end());
      pos += std::uint64_t(n) * std::uint64_t(l.precision);
    }
    if (l.records) pos += kRecordMarker;
  }
  return s;
}

// Components of a named PLOT3D field; 0 when unknown.
int field_components(const std::string& name) {
  if (name == "Density" || name == "StagnationEnergy" || name == "Pressure") return 1;
  if (name == "Momentum" || name == "Velocity") return 3;
  return 0;
}

// The field's tuples per point from a solution.
std::vector<float> field_tuples(const Solution& s, const std::string& name) {
  const std::size_t n = s.q[0].size();
  const int comps = field_components(name);
  std::vector<float> out(n * std::size_t(comps));
  for (std::size_t i = 0; i < n; ++i) {
    const double rho = s.q[0][i], e = s.q[4][i];
    const double m[3] = {s.q[1][i], s.q[2][i], s.q[3][i]};
    if (name == "Density") {
      out[i] = float(rho);
    } else if (name == "StagnationEnergy") {
      out[i] = float(e);
    } else if (name == "Pressure") {
      const double m2 = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
      out[i] = float((kGamma - 1) * (e - 0.5 * m2 / rho));
    } else {
      for (int a = 0; a < 3; ++a)
        out[3 * i + std::size_t(a)] = float(name == "Momentum" ? m[a] : m[a] / rho);
    }
  }
  return out;
}

class Plot3dSource final : public MeshSource {
 public:
  Plot3dSource(std::string input, std::vector<std::string> qs, std::string grid, FieldSpec spec)
      : input_(std::move(input)), qs_(std::move(qs)), grid_(std::move(grid)), spec_(std::move(spec)) {
    skeleton_ = read_grid(grid_, blocks_);
    std::vector<double> t;
    for (const std::string& q : qs_) {  // every step's layout checked at open (headers only)
      BinaryFile f(q);
      const Layout l = detect(f, true);
      if (l.blocks != blocks_) read_solution(q, blocks_, grid_);  // throws, naming both
      std::uint64_t pos = l.data + (l.records ? kRecordMarker : 0);
      t.push_back(reals(f, l, pos, 4)[3]);
    }
    bool increasing = true;
    for (std::size_t k = 1; k < t.size(); ++k) increasing = increasing && t[k] > t[k - 1];
    for (double v : t) increasing = increasing && std::isfinite(v);
    if (increasing && t.size() > 1) times_ = t;
  }
  int steps() const override { return int(qs_.size()); }
  std::string field() const override { return spec_.text(); }
  std::string describe() const override {
    return input_ + " on " + grid_ + ", " + spec_.name +
           (qs_.size() > 1 ? " (" + std::to_string(qs_.size()) + " .q steps)" : "");
  }
  std::vector<std::string> files() const override {
    std::vector<std::string> all{grid_};
    all.insert(all.end(), qs_.begin(), qs_.end());
    return all;
  }
  std::vector<double> times() const override { return times_; }
  Mesh read_step(int t) override {
    assert(t >= 0 && t < steps());
    const Solution s = read_solution(qs_[std::size_t(t)], blocks_, grid_);
    Mesh m = skeleton_;
    m.values = FieldSpec::reduce(field_tuples(s, spec_.name), field_components(spec_.name), spec_,
                                 qs_[std::size_t(t)] + ", field " + spec_.name);
    check_mesh(m, qs_[std::size_t(t)]);
    return m;
  }
  Aabb bounds(int) override { return skeleton_.bounds(); }

 private:
  std::string input_;
  std::vector<std::string> qs_;
  std::string grid_;
  FieldSpec spec_;
  Mesh skeleton_;  // points and cells, no values
  std::vector<BlockDims> blocks_;
  std::vector<double> times_;
};

// The only .xyz file in q's folder. Throws UsageError when there is none or several.
std::string find_grid(const std::string& q) {
  const fs::path dir = fs::path(q).parent_path().empty() ? fs::path(".") : fs::path(q).parent_path();
  std::vector<std::string> found;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
    if (io::has_suffix(e.path().filename().string(), ".xyz")) found.push_back(e.path().string());
  if (found.size() == 1) return found[0];
  std::sort(found.begin(), found.end());
  std::string list;
  for (const std::string& g : found) list += (list.empty() ? "" : ", ") + g;
  throw UsageError(q + ": a PLOT3D solution needs its grid: " +
                   (found.empty() ? std::string("no .xyz file in ") + dir.string()
                                  : std::to_string(found.size()) + " .xyz files (" + list + ")") +
                   "; name it with --xyz");
}

}  // namespace

bool is_plot3d_input(const std::string& input) {
  return io::has_suffix(input, ".q") || io::has_suffix(input, ".xyz");
}

const char* plot3d_fields() {
  return "Density, Momentum (3 components), StagnationEnergy, Velocity (3 components), Pressure";
}

std::unique_ptr<MeshSource> open_plot3d_source(const std::string& input, const std::string& grid,
                                               const FieldSpec& spec) {
  if (io::has_suffix(input, ".xyz"))
    throw UsageError(input + ": a PLOT3D grid holds no field; give the solution (.q, or a "
                     "pattern of them, one per step) as the input and the grid with --xyz " +
                     input);
  std::vector<std::string> qs;
  std::error_code ec;
  if (!fs::exists(input, ec) && io::is_file_pattern(input))
    qs = io::expand_file_pattern(input);
  else
    qs = {input};
  for (const std::string& q : qs) require_regular_file(q, "PLOT3D solution");
  FieldSpec s = spec;
  if (s.name.empty()) s.name = "Density";
  const int comps = field_components(s.name);
  if (comps == 0)
    throw FormatError(input + ": field '" + s.name + "' not found; a PLOT3D solution gives " +
                      plot3d_fields());
  FieldSpec::reduce(std::vector<float>(std::size_t(comps)), comps, s, input + ", field " + s.name);
  const std::string g = grid.empty() ? find_grid(qs[0]) : grid;
  return std::make_unique<Plot3dSource>(input, std::move(qs), g, s);
}

}  // namespace tsp
