#include "tsp/hdf5/hdf5_values.h"

#include <algorithm>
#include <cassert>

#include "tsp/core/error.h"
#include "tsp/hdf5/hdf5_handle.h"

namespace tsp::io {
namespace {

constexpr const char* kUnreadable =
    ": data cannot be read (truncated or corrupt file, or a compression filter this HDF5 "
    "library lacks)";

// Values per read batch: bounds the temporary double buffer (32 MiB) whatever the volume size.
constexpr hsize_t kBatchValues = hsize_t(1) << 22;

// An attribute open with its element type and dataspace.
struct Attribute {
  h5::Handle attr, type, space;
};

// Attribute name of obj opened with its type and dataspace; nullopt when obj has none of that
// name. Throws FormatError naming it when any of the three cannot be opened.
std::optional<Attribute> open_attribute(hid_t obj, const std::string& name,
                                        const std::string& where) {
  if (H5Aexists(obj, name.c_str()) <= 0) return std::nullopt;
  h5::Handle attr(H5Aopen(obj, name.c_str(), H5P_DEFAULT));
  h5::Handle type(attr ? H5Aget_type(attr.get()) : H5I_INVALID_HID);
  h5::Handle space(attr ? H5Aget_space(attr.get()) : H5I_INVALID_HID);
  if (!attr || !type || !space) throw FormatError(where + ": attribute " + name + " is unreadable");
  return Attribute{std::move(attr), std::move(type), std::move(space)};
}

// Strips the padding HDF5 fixed-length strings may carry.
std::string trim_padding(std::string s) {
  std::size_t nul = s.find('\0');
  if (nul != std::string::npos) s.resize(nul);
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace

bool is_standard_numeric_type(hid_t type) {
  // HDF5's own conversions trust a type's bit layout (precision, offset, exponent and mantissa
  // fields), and a crafted layout makes them read out of bounds: only the standard layouts are
  // converted.
  const hid_t standard[] = {H5T_STD_I8LE,  H5T_STD_I8BE,  H5T_STD_U8LE,    H5T_STD_U8BE,
                            H5T_STD_I16LE, H5T_STD_I16BE, H5T_STD_U16LE,   H5T_STD_U16BE,
                            H5T_STD_I32LE, H5T_STD_I32BE, H5T_STD_U32LE,   H5T_STD_U32BE,
                            H5T_STD_I64LE, H5T_STD_I64BE, H5T_STD_U64LE,   H5T_STD_U64BE,
                            H5T_IEEE_F32LE, H5T_IEEE_F32BE, H5T_IEEE_F64LE, H5T_IEEE_F64BE};
  for (hid_t t : standard)
    if (H5Tequal(type, t) > 0) return true;
  return false;
}

std::string describe_h5_type(hid_t type) {
  std::string bits = std::to_string(H5Tget_size(type) * 8) + "-bit ";
  switch (H5Tget_class(type)) {
    case H5T_INTEGER:
      return bits + (H5Tget_sign(type) == H5T_SGN_NONE ? "unsigned integer" : "signed integer");
    case H5T_FLOAT:
      return bits + "float";
    case H5T_STRING:
      return "string";
    case H5T_COMPOUND:
      return "compound";
    case H5T_ENUM:
      return "enum";
    case H5T_VLEN:
      return "variable-length sequence";
    case H5T_ARRAY:
      return "array";
    case H5T_OPAQUE:
      return "opaque";
    case H5T_BITFIELD:
      return "bitfield";
    case H5T_REFERENCE:
      return "reference";
    case H5T_TIME:
      return "time";
    default:
      return "unknown type";
  }
}

void require_numeric_dataset(hid_t dataset, const std::string& where) {
  h5::Handle type(H5Dget_type(dataset));
  if (!type) throw FormatError(where + ": cannot read the element type");
  if (!is_standard_numeric_type(type.get()))
    throw FormatError(where + ": element type is " + describe_h5_type(type.get()) +
                      ", expected an 8/16/32/64-bit integer or a 32/64-bit float");
}

std::optional<std::vector<double>> numeric_attribute(hid_t obj, const std::string& name,
                                                     const std::string& where) {
  std::optional<Attribute> a = open_attribute(obj, name, where);
  if (!a) return std::nullopt;
  const auto& [attr, type, space] = *a;
  if (!is_standard_numeric_type(type.get()))
    throw FormatError(where + ": attribute " + name + " is " + describe_h5_type(type.get()) +
                      ", expected a number");
  hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (n < 0) throw FormatError(where + ": attribute " + name + " has an unreadable shape");
  std::vector<double> values(static_cast<std::size_t>(n));
  if (n > 0 && H5Aread(attr.get(), H5T_NATIVE_DOUBLE, values.data()) < 0)
    throw FormatError(where + ": attribute " + name + " cannot be read as numbers");
  return values;
}

std::optional<std::string> string_attribute(hid_t obj, const std::string& name,
                                            const std::string& where) {
  std::optional<Attribute> a = open_attribute(obj, name, where);
  if (!a) return std::nullopt;
  const auto& [attr, type, space] = *a;
  if (H5Tget_class(type.get()) != H5T_STRING)
    throw FormatError(where + ": attribute " + name + " is " + describe_h5_type(type.get()) +
                      ", expected a string");
  if (H5Sget_simple_extent_npoints(space.get()) != 1)
    throw FormatError(where + ": attribute " + name + " holds several strings, expected one");
  h5::Handle mem(H5Tcopy(H5T_C_S1));
  if (H5Tis_variable_str(type.get()) > 0) {
    H5Tset_size(mem.get(), H5T_VARIABLE);
    H5Tset_cset(mem.get(), H5Tget_cset(type.get()));
    char* text = nullptr;
    if (H5Aread(attr.get(), mem.get(), &text) < 0)
      throw FormatError(where + ": attribute " + name + " cannot be read as a string");
    std::string s = text ? text : "";
    H5free_memory(text);
    return trim_padding(s);
  }
  std::size_t size = H5Tget_size(type.get());
  H5Tset_size(mem.get(), size + 1);
  H5Tset_cset(mem.get(), H5Tget_cset(type.get()));
  std::string s(size + 1, '\0');
  if (H5Aread(attr.get(), mem.get(), s.data()) < 0)
    throw FormatError(where + ": attribute " + name + " cannot be read as a string");
  return trim_padding(s);
}

bool converts_exactly_to_float(hid_t dataset) {
  h5::Handle type(H5Dget_type(dataset));
  if (!type) return false;
  H5T_class_t cls = H5Tget_class(type.get());
  std::size_t size = H5Tget_size(type.get());
  return (cls == H5T_FLOAT && size == 4) || (cls == H5T_INTEGER && size <= 2);
}

void read_volume(hid_t dataset, const VolumeSlab& slab, std::span<float> out,
                 const BatchConverter& convert, const std::string& where) {
  assert(!slab.spatial.empty());
  const std::size_t rank = slab.fixed.size() + slab.spatial.size() + slab.trailing;
  hsize_t plane = 1;
  for (std::size_t a = 1; a < slab.spatial.size(); ++a) plane *= slab.spatial[a];
  const hsize_t outer = slab.spatial[0];
  assert(out.size() == outer * plane);
  const hsize_t per_batch = std::max<hsize_t>(1, kBatchValues / std::max<hsize_t>(plane, 1));

  h5::Handle file_space(H5Dget_space(dataset));
  if (!file_space) throw FormatError(where + ": cannot read the dataspace");
  if (!convert) {
    // Direct path: one read into out, the memory space shaped like the file selection so
    // HDF5 copies whole contiguous runs instead of iterating element by element.
    std::vector<hsize_t> start(rank, 0), count(rank, 1);
    for (std::size_t a = 0; a < slab.fixed.size(); ++a) start[a] = slab.fixed[a];
    for (std::size_t a = 0; a < slab.spatial.size(); ++a)
      count[slab.fixed.size() + a] = slab.spatial[a];
    start[slab.fixed.size()] = slab.offset;
    if (H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(),
                            nullptr) < 0)
      throw FormatError(where + ": selection outside the dataset");
    h5::Handle mem_space(H5Screate_simple(int(rank), count.data(), nullptr));
    if (H5Dread(dataset, H5T_NATIVE_FLOAT, mem_space.get(), file_space.get(), H5P_DEFAULT,
                out.data()) < 0)
      throw FormatError(where + kUnreadable);
    return;
  }
  std::vector<double> buffer(static_cast<std::size_t>(std::min(per_batch, outer) * plane));
  std::vector<hsize_t> start(rank, 0), count(rank, 1);
  for (std::size_t a = 0; a < slab.fixed.size(); ++a) start[a] = slab.fixed[a];
  for (std::size_t a = 0; a < slab.spatial.size(); ++a)
    count[slab.fixed.size() + a] = slab.spatial[a];

  for (hsize_t o = 0; o < outer; o += per_batch) {
    const hsize_t n = std::min(per_batch, outer - o);
    start[slab.fixed.size()] = slab.offset + o;
    count[slab.fixed.size()] = n;
    const hsize_t values = n * plane;
    if (H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(),
                            nullptr) < 0)
      throw FormatError(where + ": selection outside the dataset");
    h5::Handle mem_space(H5Screate_simple(1, &values, nullptr));
    if (H5Dread(dataset, H5T_NATIVE_DOUBLE, mem_space.get(), file_space.get(), H5P_DEFAULT,
                buffer.data()) < 0)
      throw FormatError(where + kUnreadable);
    convert(std::span<const double>(buffer.data(), values),
            out.subspan(static_cast<std::size_t>(o * plane), static_cast<std::size_t>(values)));
  }
}

}  // namespace tsp::io
