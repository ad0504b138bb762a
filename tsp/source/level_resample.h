// Levels placed at their heights: a source whose z levels lie at uneven heights that differ per
// column and per step (WRF's terrain-following levels) resampled, column by column, onto a
// uniform vertical grid, linearly in height (docs/inputs.md, "WRF levels at their heights").
#pragma once
#include <functional>
#include <memory>
#include <span>
#include <string>

#include "tsp/source/volume_source.h"

namespace tsp {

/// Most levels the default (finest spacing) grid gets; a finer finest layer is coarsened to fit.
inline constexpr int kFinestLevelsCap = 256;
/// Most levels a chosen count or spacing may give.
inline constexpr int kMaxVerticalLevels = 4096;

/// Writes the height (metres, increasing with the level) of every sample of step t of a source
/// into heights (its dims().count() values, laid out as read_step's). Throws IoError/FormatError.
using LevelHeightsFn = std::function<void(int t, std::span<double> heights)>;

/// The uniform vertical grid chosen for heights of the first step.
struct VerticalPlan {
  int levels = 0;        ///< planes of the new grid
  double bottom = 0;     ///< height of plane 0 (the lowest level's lowest height), metres
  double spacing = 0;    ///< metres between planes
  double finest = 0;     ///< the thinnest layer between two stored levels, metres
  int finest_levels = 0; ///< planes the finest spacing would need (> levels when capped)
  bool capped = false;   ///< the finest spacing was coarsened to kFinestLevelsCap levels
};

/// The grid for `choice` over the heights of a stored grid (stored.count() values, laid out as
/// read_step's, stored.z ≥ 2 levels): from the lowest bottom of any column, round(range /
/// spacing) + 1 planes (finest: the thinnest layer's spacing, then stretched so that whole planes
/// end at the highest top; count: planes over the range; spacing: exactly that spacing).
/// Throws FormatError naming `where` and the column when a column's heights are not finite and
/// strictly increasing, UsageError when the choice gives fewer than 2 or more than
/// kMaxVerticalLevels levels or more than kMaxStepSamples samples a step.
VerticalPlan plan_vertical_grid(std::span<const double> heights, Dims stored,
                                const VerticalLevels& choice, const std::string& where);

/// Resamples one step: values and heights are laid out as read_step's on the stored grid; out
/// and inside are stored.x × stored.y × plan.levels. A plane at height z takes the column's value linearly
/// interpolated in height between the two levels around z; within half a plane spacing below
/// the lowest level or above the highest it takes that level's value; farther out it is
/// outside (inside 0) and padded with that level's value. Throws FormatError naming `where`
/// on heights that are not finite and strictly increasing.
void resample_columns(std::span<const float> values, std::span<const double> heights, Dims stored,
                      const VerticalPlan& plan, std::span<float> out,
                      std::span<std::uint8_t> inside, const std::string& where);

/// inner with its levels resampled at their heights (heights(t) per step) onto the uniform grid
/// `choice` picks for the first step's heights; `heights_from` names where the heights come
/// from ("geopotential") in describe(): "…, levels resampled from 14 uneven levels
/// (geopotential) to 96 at 59.5 m". The stencil marks what lies outside a column. Throws as
/// plan_vertical_grid and heights.
std::unique_ptr<VolumeSource> resample_levels(std::unique_ptr<VolumeSource> inner,
                                              LevelHeightsFn heights, const VerticalLevels& choice,
                                              const std::string& heights_from);

/// The choice written as --vertical-levels takes it: finest, native, N (a count) or Dm (a
/// spacing in metres). Never throws.
std::string to_string(const VerticalLevels& v);

/// Parses finest | native | N (2..kMaxVerticalLevels levels) | Dm (a spacing in metres > 0,
/// e.g. 50m). Throws UsageError naming `option` and what it expects.
VerticalLevels parse_vertical_levels(const std::string& text, const std::string& option);

}  // namespace tsp
