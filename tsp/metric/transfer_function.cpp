#include "tsp/metric/transfer_function.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "tsp/core/error.h"

namespace tsp {

namespace {
// Edits kept for changed_since(); older versions are answered with "everything changed".
constexpr std::size_t kMaxLoggedEdits = 4096;

void check_domain(ValueRange d) {
  if (!std::isfinite(d.lo) || !std::isfinite(d.hi) || !(d.lo < d.hi))
    throw UsageError("transfer function domain [" + std::to_string(d.lo) + ", " +
                     std::to_string(d.hi) + "] is not a finite interval with lo < hi");
}

float clamp01(float v) {
  return std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
}

Rgba clamped(Rgba c) {
  return {clamp01(c.r), clamp01(c.g), clamp01(c.b), clamp01(c.a)};
}

Rgba lerp(const Rgba& a, const Rgba& b, double t) {
  auto mix = [t](float u, float v) { return float(u + (v - u) * t); };
  return {mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b), mix(a.a, b.a)};
}
}  // namespace

// ---- ChangedEntries ----------------------------------------------------------------------------

ChangedEntries::ChangedEntries(int k) : prefix_(std::size_t(std::max(k, 0)) + 1, 0) {}

ChangedEntries ChangedEntries::all(int k) {
  ChangedEntries c(k);
  c.mark(0, k - 1);
  return c;
}

void ChangedEntries::mark(int lo, int hi) {
  const int k = int(prefix_.size()) - 1;
  lo = std::max(lo, 0);
  hi = std::min(hi, k - 1);
  if (lo > hi) return;
  std::vector<char> changed(k);
  for (int j = 0; j < k; ++j) changed[j] = prefix_[j + 1] > prefix_[j] || (j >= lo && j <= hi);
  for (int j = 0; j < k; ++j) prefix_[j + 1] = prefix_[j] + changed[j];
}

bool ChangedEntries::touches(int lo, int hi) const {
  const int k = int(prefix_.size()) - 1;
  lo = std::max(lo, 0);
  hi = std::min(hi, k - 1);
  return lo <= hi && prefix_[hi + 1] > prefix_[lo];
}

bool ChangedEntries::none() const {
  return prefix_.back() == 0;
}

// ---- TransferFunction --------------------------------------------------------------------------

TransferFunction::TransferFunction(ValueRange domain, int entries) : domain_(domain) {
  check_domain(domain);
  if (entries < 2)
    throw UsageError("transfer function needs at least 2 entries, got " + std::to_string(entries));
  table_.assign(entries, Rgba{});
  opaque_prefix_.assign(entries + 1, 0);
}

TransferFunction TransferFunction::from_points(ValueRange domain, std::span<const TfPoint> points,
                                               int entries) {
  if (points.empty()) throw UsageError("transfer function has no control points");
  std::vector<TfPoint> p(points.begin(), points.end());
  std::stable_sort(p.begin(), p.end(), [](auto& a, auto& b) { return a.x < b.x; });
  TransferFunction tf(domain, entries);
  std::vector<Rgba> colours(entries);
  std::size_t seg = 0;  // p[seg].x <= x < p[seg + 1].x while walking increasing x
  for (int j = 0; j < entries; ++j) {
    const double x = tf.entry_value(j);
    while (seg + 1 < p.size() && p[seg + 1].x <= x) ++seg;
    if (x <= p.front().x) {
      colours[j] = p.front().c;
    } else if (seg + 1 >= p.size()) {
      colours[j] = p.back().c;
    } else {
      const double w = p[seg + 1].x - p[seg].x;
      colours[j] = lerp(p[seg].c, p[seg + 1].c, w > 0 ? (x - p[seg].x) / w : 1.0);
    }
  }
  tf.set_entries(0, colours);
  return tf;
}

double TransferFunction::entry_value(int j) const {
  return domain_.lo + (j + 0.5) * (domain_.hi - domain_.lo) / size();
}

int TransferFunction::entry_of(double v) const {
  const double f = (v - domain_.lo) / (domain_.hi - domain_.lo) * size();
  if (!(f > 0)) return 0;  // also NaN
  if (f >= size()) return size() - 1;
  return int(f);
}

void TransferFunction::set_entry(int j, Rgba c) {
  set_entries(j, std::span<const Rgba>(&c, 1));
}

void TransferFunction::set_entries(int first, std::span<const Rgba> colours) {
  assert(first >= 0 && first + int(colours.size()) <= size());
  if (colours.empty()) return;
  for (std::size_t k = 0; k < colours.size(); ++k) table_[first + k] = clamped(colours[k]);
  rebuild_prefix(first);
  record(first, first + int(colours.size()) - 1);
}

void TransferFunction::set_domain(ValueRange domain) {
  check_domain(domain);
  domain_ = domain;
  record(0, size() - 1);
}

void TransferFunction::assign(const TransferFunction& next) {
  const std::uint64_t v = std::max(version_, next.version_);
  *this = next;
  version_ = v;
  log_.clear();
  log_floor_ = v;  // (older versions than the edit below: everything changed)
  record(0, size() - 1);
}

void TransferFunction::record(int lo, int hi) {
  ++version_;
  log_.push_back({version_, lo, hi});
  if (log_.size() > kMaxLoggedEdits) {
    const std::size_t drop = log_.size() - kMaxLoggedEdits / 2;
    log_floor_ = log_[drop - 1].version;
    log_.erase(log_.begin(), log_.begin() + std::ptrdiff_t(drop));
  }
}

void TransferFunction::rebuild_prefix(int from) {
  for (int j = from; j < size(); ++j) opaque_prefix_[j + 1] = opaque_prefix_[j] + (table_[j].a > 0);
}

ChangedEntries TransferFunction::changed_since(std::uint64_t since) const {
  if (since < log_floor_) return ChangedEntries::all(size());
  ChangedEntries c(size());
  for (auto it = log_.rbegin(); it != log_.rend() && it->version > since; ++it)
    c.mark(it->lo, it->hi);
  return c;
}

bool TransferFunction::touched_since(std::uint64_t since, int lo, int hi) const {
  if (since < log_floor_) return true;
  for (auto it = log_.rbegin(); it != log_.rend() && it->version > since; ++it)
    if (it->lo <= hi && lo <= it->hi) return true;
  return false;
}

bool TransferFunction::transparent(int lo, int hi) const {
  lo = std::max(lo, 0);
  hi = std::min(hi, size() - 1);
  return lo > hi || opaque_prefix_[hi + 1] == opaque_prefix_[lo];
}

ChangedEntries diff_entries(const TransferFunction& before, const TransferFunction& after) {
  if (before.size() != after.size() || !(before.domain() == after.domain()))
    return ChangedEntries::all(after.size());
  ChangedEntries c(after.size());
  int run = -1;  // start of the current run of differing entries
  for (int j = 0; j <= after.size(); ++j) {
    const bool differs = j < after.size() && !(before.entry(j) == after.entry(j));
    if (differs && run < 0) run = j;
    if (!differs && run >= 0) {
      c.mark(run, j - 1);
      run = -1;
    }
  }
  return c;
}

float corrected_opacity(float alpha, double spacing) {
  return float(1.0 - std::pow(1.0 - std::clamp(double(alpha), 0.0, 1.0), spacing));
}

std::vector<Rgba> opacity_corrected(const TransferFunction& tf, double spacing) {
  std::vector<Rgba> out(tf.entries().begin(), tf.entries().end());
  for (Rgba& c : out) c.a = corrected_opacity(c.a, spacing);
  return out;
}

}  // namespace tsp
