#include "tsp/source/level_resample.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "tsp/core/error.h"

namespace tsp {
namespace {

// The lowest bottom, the highest top and the thinnest layer of every column's heights
// (levels × columns, level-major). Throws FormatError naming `where` and the column when a
// height is not finite or not above the level below it.
struct HeightSpan {
  double bottom = std::numeric_limits<double>::infinity();
  double top = -std::numeric_limits<double>::infinity();
  double finest = std::numeric_limits<double>::infinity();
};

HeightSpan scan_heights(std::span<const double> h, Dims d, const std::string& where) {
  const std::int64_t columns = std::int64_t(d.x) * d.y;
  assert(std::int64_t(h.size()) == columns * d.z);
  HeightSpan s;
  const auto column = [&](std::int64_t c) {
    return "column (" + std::to_string(c % d.x) + ", " + std::to_string(c / d.x) + ")";
  };
  for (int k = 0; k < d.z; ++k)
    for (std::int64_t c = 0; c < columns; ++c) {
      const double z = h[std::size_t(k * columns + c)];
      if (!std::isfinite(z))
        throw FormatError(where + ": " + column(c) + ": the height of level " + std::to_string(k) +
                          " is not finite");
      if (k > 0) {
        const double below = h[std::size_t((k - 1) * columns + c)];
        if (!(z > below))
          throw FormatError(where + ": " + column(c) + ": level " + std::to_string(k) + " at " +
                            std::to_string(z) + " m is not above level " + std::to_string(k - 1) +
                            " at " + std::to_string(below) +
                            " m; the levels' heights must increase upwards");
        s.finest = std::min(s.finest, z - below);
      }
      if (k == 0) s.bottom = std::min(s.bottom, z);
      if (k == d.z - 1) s.top = std::max(s.top, z);
    }
  return s;
}

// Planes of a grid from bottom at `spacing` that end nearest the top: round(range/spacing) + 1,
// as a double so that a huge count is compared before any narrowing.
double planes_for(double range, double spacing) {
  return std::round(range / spacing) + 1;
}

std::string metres(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f m", v);
  return text;
}

class LevelResampledSource final : public VolumeSource {
 public:
  LevelResampledSource(std::unique_ptr<VolumeSource> inner, LevelHeightsFn heights,
                       VerticalPlan plan, std::string note)
      : inner_(std::move(inner)), heights_(std::move(heights)), plan_(plan), note_(std::move(note)) {}

  Dims dims() const override {
    Dims d = inner_->dims();
    d.z = plan_.levels;
    return d;
  }
  int steps() const override { return inner_->steps(); }
  std::string describe() const override { return inner_->describe() + ", " + note_; }
  std::string field() const override { return inner_->field(); }
  std::vector<std::string> files() const override { return inner_->files(); }
  std::vector<double> times() const override { return inner_->times(); }
  TimeUnits time_units() const override { return inner_->time_units(); }
  std::array<double, 3> origin() const override {
    std::array<double, 3> o = inner_->origin();
    o[2] = plan_.bottom;
    return o;
  }
  std::array<double, 3> spacing() const override {
    std::array<double, 3> s = inner_->spacing();
    s[2] = plan_.spacing;
    return s;
  }
  bool has_stencil() const override { return true; }

  void read_step(int t, std::span<float> out) override {
    std::vector<std::uint8_t> inside(out.size());
    read_step_inside(t, out, inside);
  }

  void read_step_inside(int t, std::span<float> out, std::span<std::uint8_t> inside) override {
    const Dims d = inner_->dims();
    values_.resize(std::size_t(d.count()));
    heights_of_step_.resize(std::size_t(d.count()));
    inner_->read_step(t, values_);
    heights_(t, heights_of_step_);
    resample_columns(values_, heights_of_step_, d, plan_, out, inside,
                     describe() + ", step " + std::to_string(t));
  }

 private:
  std::unique_ptr<VolumeSource> inner_;
  LevelHeightsFn heights_;
  VerticalPlan plan_;
  std::string note_;
  std::vector<float> values_;            // one step of the stored levels
  std::vector<double> heights_of_step_;  // their heights
};

}  // namespace

VerticalPlan plan_vertical_grid(std::span<const double> heights, Dims stored,
                                const VerticalLevels& choice, const std::string& where) {
  assert(stored.z >= 2 && choice.mode != VerticalLevels::Mode::native);
  const std::int64_t columns = std::int64_t(stored.x) * stored.y;
  const HeightSpan s = scan_heights(heights, stored, where);
  VerticalPlan p;
  p.bottom = s.bottom;
  p.finest = s.finest;
  const double range = s.top - s.bottom;
  double planes = 0;
  switch (choice.mode) {
    case VerticalLevels::Mode::finest:  // whole planes over the range, the nearest the finest
      planes = planes_for(range, s.finest);
      if (planes > kFinestLevelsCap) {
        p.capped = true;
        planes = kFinestLevelsCap;
      }
      p.spacing = range / (planes - 1);
      break;
    case VerticalLevels::Mode::count:
      planes = choice.levels;
      p.spacing = range / (choice.levels - 1);
      break;
    case VerticalLevels::Mode::spacing:
      if (!(choice.spacing <= range))
        throw UsageError(where + ": --vertical-levels " + to_string(choice) +
                         ": the spacing is larger than the levels' whole range, " + metres(range) +
                         " (" + metres(s.bottom) + " to " + metres(s.top) + ")");
      planes = planes_for(range, choice.spacing);
      p.spacing = choice.spacing;
      break;
    case VerticalLevels::Mode::native:
      break;
  }
  if (!(planes >= 2 && planes <= kMaxVerticalLevels))
    throw UsageError(where + ": --vertical-levels " + to_string(choice) + " would make " +
                     (planes > 1e12 ? std::string("more than 10^12")
                                    : std::to_string(std::int64_t(planes))) +
                     " levels over " + metres(range) + "; at most " +
                     std::to_string(kMaxVerticalLevels) + " (choose a coarser spacing)");
  if (planes * double(columns) > double(kMaxStepSamples))
    throw UsageError(where + ": --vertical-levels " + to_string(choice) + " would make " +
                     std::to_string(std::int64_t(planes)) + " levels of " +
                     std::to_string(columns) + " columns, more than " +
                     std::to_string(kMaxStepSamples) + " samples a step");
  p.levels = int(planes);
  p.finest_levels = int(std::min(planes_for(range, s.finest), 1e9));
  return p;
}

void resample_columns(std::span<const float> values, std::span<const double> heights, Dims stored,
                      const VerticalPlan& plan, std::span<float> out,
                      std::span<std::uint8_t> inside, const std::string& where) {
  const int levels = stored.z;
  const std::int64_t columns = std::int64_t(stored.x) * stored.y;
  assert(levels >= 2 && std::int64_t(values.size()) == columns * levels &&
         heights.size() == values.size());
  assert(std::int64_t(out.size()) == columns * plan.levels && inside.size() == out.size());
  (void)scan_heights(heights, stored, where);
  const auto H = [&](int k, std::int64_t c) { return heights[std::size_t(k * columns + c)]; };
  const auto V = [&](int k, std::int64_t c) { return double(values[std::size_t(k * columns + c)]); };
  const double half = 0.5 * plan.spacing;
  std::vector<int> below(std::size_t(columns), 0);  // per column: the level at or below z
  for (int j = 0; j < plan.levels; ++j) {
    const double z = plan.bottom + j * plan.spacing;
    for (std::int64_t c = 0; c < columns; ++c) {
      int& k = below[std::size_t(c)];
      while (k + 1 < levels - 1 && H(k + 1, c) <= z) ++k;
      const std::size_t o = std::size_t(j * columns + c);
      double v;
      bool in = true;
      if (z < H(0, c)) {
        v = V(0, c);
        in = H(0, c) - z <= half;
      } else if (z > H(levels - 1, c)) {
        v = V(levels - 1, c);
        in = z - H(levels - 1, c) <= half;
      } else {
        const double a = H(k, c), b = H(k + 1, c);
        v = V(k, c) + (z - a) / (b - a) * (V(k + 1, c) - V(k, c));
      }
      out[o] = float(v);
      inside[o] = in ? 1 : 0;
    }
  }
}

std::unique_ptr<VolumeSource> resample_levels(std::unique_ptr<VolumeSource> inner,
                                              LevelHeightsFn heights, const VerticalLevels& choice,
                                              const std::string& heights_from) {
  const Dims d = inner->dims();
  const std::string where = inner->describe();
  if (d.z < 2)
    throw FormatError(where + ": " + std::to_string(d.z) +
                      " level: resampling at heights needs at least 2");
  std::vector<double> first(std::size_t(d.count()));
  heights(0, first);
  const VerticalPlan plan =
      plan_vertical_grid(first, d, choice, where + ", step 0");
  std::string note = "levels resampled from " + std::to_string(d.z) + " uneven levels (" +
                     heights_from + ") to " + std::to_string(plan.levels) + " at " +
                     metres(plan.spacing);
  if (plan.capped)
    note += " (capped at " + std::to_string(kFinestLevelsCap) + " levels: the finest layer, " +
            metres(plan.finest) + ", would need " + std::to_string(plan.finest_levels) + ")";
  return std::make_unique<LevelResampledSource>(std::move(inner), std::move(heights), plan,
                                                std::move(note));
}

std::string to_string(const VerticalLevels& v) {
  switch (v.mode) {
    case VerticalLevels::Mode::finest:
      return "finest";
    case VerticalLevels::Mode::native:
      return "native";
    case VerticalLevels::Mode::count:
      return std::to_string(v.levels);
    case VerticalLevels::Mode::spacing: {
      char text[40];
      std::snprintf(text, sizeof text, "%gm", v.spacing);
      return text;
    }
  }
  return "finest";
}

VerticalLevels parse_vertical_levels(const std::string& text, const std::string& option) {
  const auto bad = [&] {
    return UsageError(option + " '" + text +
                      "': expected finest, native, a level count N (2 to " +
                      std::to_string(kMaxVerticalLevels) +
                      ") or a spacing in metres such as 50m");
  };
  VerticalLevels v;
  if (text == "finest") return v;
  if (text == "native") {
    v.mode = VerticalLevels::Mode::native;
    return v;
  }
  if (!text.empty() && text.size() <= 6 &&
      std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    const int n = std::stoi(text);
    if (n < 2 || n > kMaxVerticalLevels) throw bad();
    v.mode = VerticalLevels::Mode::count;
    v.levels = n;
    return v;
  }
  if (text.size() >= 2 && text.back() == 'm') {
    const std::string number = text.substr(0, text.size() - 1);
    std::size_t used = 0;
    double s = 0;
    try {
      s = std::stod(number, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == number.size() && std::isfinite(s) && s > 0) {
      v.mode = VerticalLevels::Mode::spacing;
      v.spacing = s;
      return v;
    }
  }
  throw bad();
}

}  // namespace tsp
