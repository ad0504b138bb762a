// A render's frame set: the names in its output folder (step_NNNN.png, frames.json), and how a
// render split over processes (tspplay-mpi render, docs/mpi.md) cuts the frames into parts and
// joins the parts' frames.json into the one the serial render writes. GL-free and HDF5-free:
// tspplay-mpi compiles this file against its own core library.
#pragma once
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace tspgl {

/// Whether name belongs to a render's frame set (step_NNNN.png, frames.json): what replacing the
/// output folder drops; other files there are kept. Never throws.
bool is_frame_set_name(const std::string& name);

/// The PNG path of step under dir: dir/step_NNNN.png. Never throws.
std::string step_png(const std::filesystem::path& dir, int step);

/// The upper median of v (the element at index size/2 once sorted; 0 for none), as every
/// frame-time summary of the jobs reports it. Never throws.
double median(std::vector<double> v);

/// The frames [first, end) of a pass of `frames` frames (0-based, in the order rendered) that
/// part `part` of `parts` draws: consecutive blocks in part order whose sizes differ by at most
/// one, so consecutive steps (a span sharing a texture) stay together. Asserts 0 <= part < parts.
std::pair<int, int> part_frames(int frames, int part, int parts);

/// The serial render's frames.json from the parts' (in part order, each written by a render of
/// part r, its frames carrying "rank": r): every key of part 0's, the frames ordered by pass and
/// then by part (the serial order), median_ms over the last pass's frames, metric_ms the largest
/// part's, plus "ranks" (the part count) and "rank_contexts" (each part's rank, context,
/// renderer, gl_vendor, metric_ms and frame count). Throws tsp::FormatError when a part is not an
/// object with a "frames" array of objects with integer "pass" and number "ms".
nlohmann::json merge_part_frames(const std::vector<nlohmann::json>& parts);

}  // namespace tspgl
