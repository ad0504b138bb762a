// Transfer function (spec §3): K RGBA entries over a scalar domain, an edit version counter and
// the entries each edit changed, plus opacity correction for sample spacing (spec §9).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "tsp/core/types.h"

namespace tsp {

/// Default number of transfer-function entries K.
inline constexpr int kDefaultTfEntries = 256;

/// One colour with opacity, every component in [0, 1].
struct Rgba {
  float r = 0, g = 0, b = 0, a = 0;
  bool operator==(const Rgba&) const = default;
};

/// A control point of a piecewise-linear transfer function, x in data units.
struct TfPoint {
  double x = 0;
  Rgba c;
};

/// Which entries changed: answers "does [lo, hi] hold a changed entry?" in O(1).
class ChangedEntries {
 public:
  /// No entry changed, over k entries.
  explicit ChangedEntries(int k = 0);
  /// Every entry of k changed.
  static ChangedEntries all(int k);
  /// Marks entries [lo, hi] (clamped to the table) changed; O(K).
  void mark(int lo, int hi);
  /// True when some entry in [lo, hi] (clamped) changed.
  bool touches(int lo, int hi) const;
  /// True when no entry changed.
  bool none() const;

 private:
  std::vector<int> prefix_;  // prefix_[j] = number of changed entries below j (K + 1 values)
};

/// K RGBA entries; entry j represents x(j) = lo + (j + 0.5)·(hi − lo)/K of the domain [lo, hi].
/// Every edit bumps version() and is logged, so callers can ask what changed since a version.
class TransferFunction {
 public:
  /// A fully transparent black table of `entries` entries over domain. Throws UsageError when
  /// entries < 2 or the domain is not finite with lo < hi.
  explicit TransferFunction(ValueRange domain = {0, 1}, int entries = kDefaultTfEntries);
  /// Samples a piecewise-linear function through points (sorted by x here; constant beyond the
  /// first and last point) at every entry centre. Throws UsageError on an empty point list.
  static TransferFunction from_points(ValueRange domain, std::span<const TfPoint> points,
                                      int entries = kDefaultTfEntries);

  /// Scalar domain [s_min, s_max] in data units.
  ValueRange domain() const { return domain_; }
  /// Number of entries K.
  int size() const { return int(table_.size()); }
  /// Entry j.
  const Rgba& entry(int j) const { return table_[j]; }
  /// All entries.
  std::span<const Rgba> entries() const { return table_; }
  /// Scalar value x(j) at the centre of entry j.
  double entry_value(int j) const;
  /// Entry of value v: floor((v − lo)/(hi − lo)·K), clamped to [0, K−1]; NaN maps to 0.
  int entry_of(double v) const;
  /// Colour of value v (the entry holding v, no interpolation).
  const Rgba& lookup(double v) const { return table_[entry_of(v)]; }

  /// Replaces entry j (components clamped to [0, 1]); one edit.
  void set_entry(int j, Rgba c);
  /// Replaces entries [first, first + colours.size()); one edit.
  void set_entries(int first, std::span<const Rgba> colours);
  /// Moves the table to a new domain; one edit that changes every entry.
  /// Throws UsageError on an empty or non-finite domain.
  void set_domain(ValueRange domain);

  /// Takes next's domain and entries as one edit of this table that changes every entry:
  /// version() grows past both tables' versions (a copy takes next's, which may be lower, so
  /// whatever keys on the version — a player's LOD loop, tuning, metric, trace — missed it).
  void assign(const TransferFunction& next);

  /// Edit counter: starts at 0 and grows by one with every edit.
  std::uint64_t version() const { return version_; }
  /// Entries changed by the edits after `since` (every entry when the log no longer reaches back).
  ChangedEntries changed_since(std::uint64_t since) const;
  /// True when an edit after `since` changed an entry in [lo, hi]; cost O(edits since).
  bool touched_since(std::uint64_t since, int lo, int hi) const;

  /// Largest α over entries [lo, hi] is 0 (spec §3's exact transparency test); O(1).
  bool transparent(int lo, int hi) const;

 private:
  struct Edit {
    std::uint64_t version;
    int lo, hi;
  };
  ValueRange domain_;
  std::vector<Rgba> table_;
  std::vector<int> opaque_prefix_;  // opaque_prefix_[j] = #entries < j with α > 0
  std::vector<Edit> log_;
  std::uint64_t version_ = 0;
  std::uint64_t log_floor_ = 0;  // the log holds every edit after this version
  void record(int lo, int hi);
  void rebuild_prefix(int from);
};

/// Entries that differ between two tables (every entry when domains or sizes differ).
ChangedEntries diff_entries(const TransferFunction& before, const TransferFunction& after);

/// Opacity corrected for a sample spacing of `spacing` voxels (Δ/Δ₀ with Δ₀ = one voxel) when
/// the TF's opacity is per voxel (spec §9): α' = 1 − (1 − α)^spacing with α clamped to [0, 1]
/// (NaN stays NaN). The one correction the renderer uploads (src/render) and the metrics use.
/// Expects spacing > 0. Never throws.
float corrected_opacity(float alpha, double spacing);

/// The table with every α corrected for `spacing` voxels between samples (colours unchanged).
std::vector<Rgba> opacity_corrected(const TransferFunction& tf, double spacing);

}  // namespace tsp
