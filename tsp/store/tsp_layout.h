// Names inside a .tsp file, shared by its writer and reader. The layout is documented in
// docs/formats.md; change both together and bump kTspFormatVersion (tsp/tsp_file.h).
#pragma once
#include <string>
#include <array>

#include "tsp/tree/octree.h"

namespace tsp {

/// Brick extent as stored in /bricks/data along x, y, z: the largest brick's samples (≤ B);
/// smaller edge bricks are padded by repeating their last sample. Never throws.
inline std::array<int, 3> stored_brick_shape(const Octree& octree) {
  return octree.max_brick_samples();
}

}  // namespace tsp

namespace tsp::layout {

inline constexpr const char* kFormatName = "tspplay";

// Root attributes.
inline constexpr const char* kAttrFormat = "format";
inline constexpr const char* kAttrVersion = "version";
inline constexpr const char* kAttrDims = "dims";               // int32[3]: x, y, z
inline constexpr const char* kAttrSteps = "steps";             // int32
inline constexpr const char* kAttrBrickSize = "brick_size";    // int32
inline constexpr const char* kAttrValueRange = "value_range";  // float64[2]: quantization range
inline constexpr const char* kAttrDataRange = "data_range";    // float64[2]: finite input range
inline constexpr const char* kAttrSource = "source";
inline constexpr const char* kAttrField = "field";
inline constexpr const char* kAttrCreatedBy = "created_by";
inline constexpr const char* kAttrNonfinite = "nonfinite_count";  // int64
// int32: processes that built the file (tspplay-mpi); 1 for the serial build; absent: 1.
inline constexpr const char* kAttrBuildRanks = "build_ranks";
inline constexpr const char* kAttrQuantization = "quantization";  // text of the rule
inline constexpr const char* kAttrNodeId = "tsp_node_id";         // text of the id rule
inline constexpr const char* kAttrOrigin = "origin";    // float64[3]: voxel (0,0,0) in space
inline constexpr const char* kAttrSpacing = "spacing";  // float64[3]: voxel spacing per axis
// Text, on kTimeValues when the input named them: CF-style units and calendar of the times.
inline constexpr const char* kAttrTimeUnits = "units";
inline constexpr const char* kAttrTimeCalendar = "calendar";
// Root only, files with several fields: their names in order, one per line (the first is the
// root's own field).
inline constexpr const char* kAttrFields = "fields";
inline constexpr const char* kFieldsGroup = "fields";  // holds one group per further field, "1", …
/// The location of field k: the root for k = 0, fields/K for k ≥ 1. Never throws but bad_alloc.
inline std::string field_group(int k) {
  return k == 0 ? std::string("/") : std::string(kFieldsGroup) + "/" + std::to_string(k);
}

// Datasets and groups, relative to the field's location: the file's root for its first field,
// fields/K for field K ≥ 1 of a file with several (kAttrFields lists them).
inline constexpr const char* kBricks = "bricks";
// uint16 [nb+nl,T,Bz,By,Bx]: the nb leaf bricks, then the nl level bricks (format 2)
inline constexpr const char* kBrickData = "bricks/data";
// uint8, the shape of /bricks/data, only for inputs with a stencil: 1 = inside the data
inline constexpr const char* kBrickInside = "bricks/inside";
inline constexpr const char* kBrickSamplesBox = "bricks/samples_box";  // int32 [nb,6]
inline constexpr const char* kBrickOwnBox = "bricks/own_box";          // int32 [nb,6]
inline constexpr const char* kLevels = "levels";
inline constexpr const char* kLevelNode = "levels/node";        // int32 [nl]: octree node
inline constexpr const char* kLevelLattice = "levels/lattice";  // int32 [nl,9]: origin, factor, samples
inline constexpr const char* kLevelError = "levels/error";      // float32 [nl,T]: RMS residual
inline constexpr const char* kOctree = "octree";
inline constexpr const char* kOctreeBox = "octree/box";            // int32 [no,6]
inline constexpr const char* kOctreeLevel = "octree/level";        // int32 [no]
inline constexpr const char* kOctreeParent = "octree/parent";      // int32 [no]
inline constexpr const char* kOctreeChildren = "octree/children";  // int32 [no,8]
inline constexpr const char* kOctreeBrick = "octree/brick";        // int32 [no]
inline constexpr const char* kOctreeInside = "octree/inside";      // float32 [no], with a stencil
// uint8 [no], version 3 only: 1 where the data ends at an internal node (adaptive builds)
inline constexpr const char* kOctreeStopped = "octree/stopped";
inline constexpr const char* kTime = "time";
inline constexpr const char* kTimeSpan = "time/span";  // int32 [2T-1,2]
inline constexpr const char* kTimeValues = "time/values";  // float64 [T], when the input names them
inline constexpr const char* kStats = "stats";
inline constexpr const char* kStatsMean = "stats/mean";                // float64 [n]
inline constexpr const char* kStatsStd = "stats/std";                  // float64 [n]
inline constexpr const char* kStatsMin = "stats/min";                  // float32 [n]
inline constexpr const char* kStatsMax = "stats/max";                  // float32 [n]
inline constexpr const char* kStatsSpatial = "stats/spatial_error";    // float32 [n]
inline constexpr const char* kStatsTemporal = "stats/temporal_error";  // float32 [n]
inline constexpr const char* kHistogram = "histogram";                 // uint64 [kHistogramBins]

inline constexpr const char* kQuantizationRule =
    "code q in [0,65535] stands for v = lo + q*(hi-lo)/65535 with [lo,hi] = value_range; "
    "q = round_half_even((clamp(v,lo,hi)-lo)/(hi-lo)*65535), 0 when hi == lo; "
    "NaN and -Inf become lo, +Inf becomes hi";
inline constexpr const char* kLevelRule =
    "level brick of internal node n: sample j along axis a at voxel origin[a] + j*factor[a] "
    "(clamped to the grid), factor = power of two >= n's brick range; value = separable box "
    "filter of width factor centred there (weights 1/2,1,...,1,1/2; window shrunk symmetrically "
    "at the grid faces); stored in /bricks/data after the leaf bricks, padded like them";
inline constexpr const char* kAttrLevelRule = "level_rule";
inline constexpr const char* kNodeIdRule =
    "TSP node id = octree_id * (2*steps - 1) + time_id; octree and time nodes breadth-first";

}  // namespace tsp::layout
