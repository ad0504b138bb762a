#include "tsp/metric/histogram_tf.h"

#include <algorithm>
#include <cmath>

#include "tsp/core/error.h"
#include "tsp/metric/tf_io.h"

namespace tsp {

namespace detail {

bool valid(ValueRange r) {
  return std::isfinite(r.lo) && std::isfinite(r.hi) && r.lo < r.hi && std::isfinite(r.width());
}

}  // namespace detail

std::vector<double> histogram_rarity(std::span<const std::uint64_t> counts) {
  const int n = int(counts.size());
  std::vector<double> smooth(counts.size(), 0.0);
  for (int i = 0; i < n; ++i) {
    double sum = 0, weight = 0;
    for (int d = -kHistogramTfSmoothBins; d <= kHistogramTfSmoothBins; ++d) {
      const int j = i + d;
      if (j < 0 || j >= n) continue;
      const double w = kHistogramTfSmoothBins + 1 - std::abs(d);
      sum += w * double(counts[std::size_t(j)]);
      weight += w;
    }
    smooth[std::size_t(i)] = sum / weight;
  }
  double lmax = -1, lmin = -1;
  std::vector<double> l(counts.size(), 0.0);
  for (int i = 0; i < n; ++i) {
    if (smooth[std::size_t(i)] <= 0) continue;
    const double v = std::log1p(smooth[std::size_t(i)]);
    l[std::size_t(i)] = v;
    lmax = lmax < 0 ? v : std::max(lmax, v);
    lmin = lmin < 0 ? v : std::min(lmin, v);
  }
  std::vector<double> rarity(counts.size(), kHistogramTfFlatRarity);
  if (!(lmax > lmin)) return rarity;
  for (int i = 0; i < n; ++i)
    rarity[std::size_t(i)] =
        smooth[std::size_t(i)] <= 0 ? 1.0
                                    : std::clamp((lmax - l[std::size_t(i)]) / (lmax - lmin), 0.0, 1.0);
  return rarity;
}

std::vector<double> histogram_tail_share(std::span<const std::uint64_t> counts) {
  double total = 0;
  for (std::uint64_t c : counts) total += double(c);
  std::vector<double> tail(counts.size(), 1.0);
  if (!(total > 0)) return tail;
  double below = 0;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const double f = (below + 0.5 * double(counts[i])) / total;
    tail[i] = std::min(f, 1 - f);
    below += double(counts[i]);
  }
  return tail;
}

TransferFunction histogram_transfer_function(const ValueHistogram& h, ValueRange domain,
                                             int entries) {
  if (!detail::valid(domain) || !detail::valid(h.over))
    throw UsageError("histogram transfer function: the domain and the histogram's range must be "
                     "finite with lo < hi");
  // Colours: the cool-to-warm preset's, over the domain (throws on entries < 2).
  TransferFunction tf = preset_transfer_function("cool-to-warm", domain, entries);
  // Rarity among the bins the domain overlaps: a map over part of the data (one step's range, a
  // chosen interval) still makes its own rarest values opaque.
  const int bins = int(h.counts.size());
  const auto bin_of = [&](double v) {
    return int(std::floor((v - h.over.lo) / h.over.width() * bins));
  };
  const int first = std::clamp(bin_of(domain.lo), 0, std::max(0, bins - 1));
  const int last = std::clamp(bin_of(domain.hi), 0, std::max(0, bins - 1));
  std::vector<double> rarity(h.counts.size(), 1.0), tail(h.counts.size(), 1.0);
  if (bins > 0 && first <= last) {
    const auto part = h.counts.subspan(std::size_t(first), std::size_t(last - first + 1));
    const std::vector<double> r = histogram_rarity(part), s = histogram_tail_share(part);
    std::copy(r.begin(), r.end(), rarity.begin() + first);
    std::copy(s.begin(), s.end(), tail.begin() + first);
  }
  std::vector<Rgba> colours(std::size_t(tf.size()));
  for (int j = 0; j < tf.size(); ++j) {
    const double x = tf.entry_value(j);
    const double u = (x - h.over.lo) / h.over.width();
    double r = 1.0, s = 1.0;  // outside the histogram's span no sample takes the value
    if (bins > 0 && u >= 0 && u <= 1) {
      const std::size_t b = std::size_t(std::min(bins - 1, int(u * bins)));
      r = rarity[b];
      s = tail[b];
    }
    if (bins == 0) r = kHistogramTfFlatRarity;
    Rgba c = tf.entry(j);
    const double by_rarity =
        r < kHistogramTfClearRarity ? 0.0 : kHistogramTfMaxOpacity * std::pow(r, kHistogramTfGamma);
    const double by_tail =
        s < kHistogramTfTailShare
            ? kHistogramTfMaxOpacity * std::pow(1 - s / kHistogramTfTailShare, kHistogramTfGamma)
            : 0.0;
    c.a = float(std::max(by_rarity, by_tail));
    colours[std::size_t(j)] = c;
  }
  tf.set_entries(0, colours);
  return tf;
}

}  // namespace tsp
