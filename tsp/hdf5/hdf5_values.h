// Typed access to HDF5 datasets and attributes for the readers: element-type checks,
// numeric and string attributes, and batched reads of a volume into floats.
#pragma once
#include <hdf5.h>

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace tsp::io {

/// Names an HDF5 type for messages: "32-bit float", "16-bit signed integer", "string", ….
/// Never throws.
std::string describe_h5_type(hid_t type);

/// Throws FormatError (naming `where`, e.g. "a.h5, dataset /T", and the type found) unless the
/// dataset's elements are 8/16/32/64-bit integers or 32/64-bit floats.
void require_numeric_dataset(hid_t dataset, const std::string& where);

/// Reads attribute `name` of obj as doubles (any numeric type, any number of elements);
/// nullopt when absent. Throws FormatError naming `where` when it is not numeric.
std::optional<std::vector<double>> numeric_attribute(hid_t obj, const std::string& name,
                                                     const std::string& where);

/// Reads string attribute `name` of obj (fixed or variable length, trailing NULs/spaces
/// dropped); nullopt when absent. Throws FormatError naming `where` when it is not a string.
std::optional<std::string> string_attribute(hid_t obj, const std::string& name,
                                            const std::string& where);

/// Which elements of a dataset form one volume: fixed indices for the leading dimensions
/// (e.g. the time index), then spatial dimensions (outermost first, x last: whole, except the
/// outermost, read from index `offset`), then `trailing` more dimensions read at index 0 (a
/// component axis of size 1).
struct VolumeSlab {
  std::vector<hsize_t> fixed;
  std::vector<hsize_t> spatial;
  hsize_t offset = 0;
  int trailing = 0;
};

/// True when type is one of HDF5's standard integer (8–64 bit, signed or not) or IEEE float
/// (32/64 bit) layouts, in either byte order: the only numeric types converted (a crafted bit
/// layout crashes HDF5's conversion). Never throws.
bool is_standard_numeric_type(hid_t type);

/// True when every value of dataset's element type is a float32 exactly (float32, ints of ≤ 16 bits).
bool converts_exactly_to_float(hid_t dataset);

/// Converts one batch of values read as doubles into floats (same length).
using BatchConverter = std::function<void(std::span<const double>, std::span<float>)>;

/// Reads the slab of dataset into out (product of slab.spatial floats, x fastest) in batches
/// of outer planes, passing each batch through convert; an empty convert reads float32 directly
/// in one call (use it only when the file type converts to float exactly or as the caller wants). Throws FormatError naming `where`
/// when HDF5 cannot read the data (truncated file, corrupt chunk, unavailable filter).
void read_volume(hid_t dataset, const VolumeSlab& slab, std::span<float> out,
                 const BatchConverter& convert, const std::string& where);

}  // namespace tsp::io
