// Reading a .tsp file's layout (tsp_layout.h) with every inconsistency a FormatError naming
// the file and the object: attributes and datasets of checked type and shape, the format tag,
// a field's physical box. Internal to tsp/store (tsp_file.cpp); not a public header.
#pragma once
#include <string>
#include <vector>

#include "tsp/core/error.h"
#include "tsp/core/geometry.h"
#include "tsp/hdf5/hdf5_handle.h"
#include "tsp/hdf5/hdf5_values.h"

namespace tsp::detail {

using h5::Handle;

/// "[a,b,c]" for messages.
std::string shape_text(const std::vector<hsize_t>& s);

/// Reads the .tsp layout of one open field, turning every inconsistency into a FormatError
/// that names the file and the object. Not thread-safe: under the HDF5 lock.
class Reader {
 public:
  /// file: the field's location (the root group or fields/K); prefix: its path for messages.
  Reader(const std::string& path, hid_t file, std::string prefix = "/")
      : path_(path), file_(file), prefix_(std::move(prefix)) {}

  /// "dataset /NAME" (with the field's group) for messages.
  std::string dataset_name(const char* name) const { return "dataset " + prefix_ + name; }

  /// Throws FormatError "PATH: what: msg".
  [[noreturn]] void fail(const std::string& what, const std::string& msg) const {
    throw FormatError(path_ + ": " + what + ": " + msg);
  }

  /// True when the field's location has attribute name.
  bool has_attr(const char* name) const { return H5Aexists(file_, name) > 0; }

  /// Attribute name, opened; FormatError when missing or unopenable.
  Handle open_attr(const char* name) const {
    if (!has_attr(name)) fail(std::string("attribute ") + name, "missing");
    Handle a(H5Aopen(file_, name, H5P_DEFAULT));
    if (!a) fail(std::string("attribute ") + name, "cannot be opened");
    return a;
  }

  /// The one string-attribute reader (hdf5/hdf5_values); a missing one is an error here.
  std::string attr_string(const char* name) const {
    if (!has_attr(name)) fail(std::string("attribute ") + name, "missing");
    return *io::string_attribute(file_, name, path_);
  }

  /// Attribute name's `count` numbers of a standard type, as T.
  template <class T>
  std::vector<T> attr_numbers(const char* name, hid_t mem_type, hssize_t count) const {
    Handle a = open_attr(name);
    Handle type(H5Aget_type(a.get()));
    if (!io::is_standard_numeric_type(type.get()))
      fail(std::string("attribute ") + name, "expected numbers of a standard integer or float type");
    Handle space(H5Aget_space(a.get()));
    hssize_t n = H5Sget_simple_extent_npoints(space.get());
    if (n != count)
      fail(std::string("attribute ") + name,
           "expected " + std::to_string(count) + " value(s), found " + std::to_string(n));
    std::vector<T> v(static_cast<std::size_t>(count));
    if (H5Aread(a.get(), mem_type, v.data()) < 0)
      fail(std::string("attribute ") + name, "unreadable");
    return v;
  }

  /// Dataset name, checked to have `shape` and a standard type of class cls.
  Handle open_dataset(const char* name, const std::vector<hsize_t>& shape, H5T_class_t cls) const {
    if (!h5::exists(file_, name)) fail(dataset_name(name), "missing");
    Handle ds(H5Dopen2(file_, name, H5P_DEFAULT));
    if (!ds) fail(dataset_name(name), "cannot be opened");
    auto found = h5::dataset_shape(ds.get());
    if (found != shape)
      fail(dataset_name(name),
           "expected shape " + shape_text(shape) + ", found " + shape_text(found));
    Handle type(H5Dget_type(ds.get()));
    if (H5Tget_class(type.get()) != cls || !io::is_standard_numeric_type(type.get()))
      fail(dataset_name(name),
           cls == H5T_FLOAT ? "expected floating-point values of a standard type"
                            : "expected integers of a standard type");
    return ds;
  }

  /// Dataset name read whole (open_dataset's checks) as T.
  template <class T>
  std::vector<T> dataset(const char* name, const std::vector<hsize_t>& shape, hid_t mem_type,
                         H5T_class_t cls) const {
    Handle ds = open_dataset(name, shape, cls);
    std::size_t n = 1;
    for (hsize_t d : shape) n *= d;
    std::vector<T> v(n);
    if (n > 0 && H5Dread(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
      fail(dataset_name(name), "unreadable (truncated or corrupt file?)");
    return v;
  }

  /// FormatError unless dataset name's values `found` are `want` (the dims' and brick size's).
  template <class T>
  void expect_equal(const char* name, const std::vector<T>& found,
                    const std::vector<T>& want) const {
    if (found.size() != want.size()) fail(dataset_name(name), "wrong size");
    for (std::size_t i = 0; i < want.size(); ++i)
      if (found[i] != want[i])
        fail(dataset_name(name),
             "element " + std::to_string(i) + " is " + std::to_string(found[i]) + ", expected " +
                 std::to_string(want[i]) + " for the file's dims and brick size");
  }

 private:
  std::string path_;
  hid_t file_;
  std::string prefix_;
};

/// Checks the format tag and version of a field's location. Throws FormatError.
void check_format(const Reader& r, const std::string& path);

/// Field r's physical box, origin .. origin + (dims − 1)·spacing, from its attributes (origin
/// and spacing default to 0 and 1). Throws FormatError naming the field's group.
Aabb field_box(const Reader& r);

}  // namespace tsp::detail
