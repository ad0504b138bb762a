#include "tsp/store/tsp_reader.h"

#include <array>
#include <sstream>

#include "tsp/store/tsp_file.h"
#include "tsp/store/tsp_layout.h"

namespace tsp::detail {

std::string shape_text(const std::vector<hsize_t>& s) {
  std::ostringstream o;
  o << "[";
  for (std::size_t i = 0; i < s.size(); ++i) o << (i ? "," : "") << s[i];
  o << "]";
  return o.str();
}

void check_format(const Reader& r, const std::string& path) {
  if (!r.has_attr(layout::kAttrFormat))
    throw FormatError(path +
                      ": not a tspplay .tsp file (HDF5 without a 'format' attribute; "
                      "an unfinished build or another kind of file)");
  std::string format = r.attr_string(layout::kAttrFormat);
  if (format != layout::kFormatName)
    r.fail("attribute format",
           "expected \"" + std::string(layout::kFormatName) + "\", found \"" + format + "\"");
  int version = r.attr_numbers<int>(layout::kAttrVersion, H5T_NATIVE_INT, 1)[0];
  if (version != kTspFormatVersion && version != kTspAdaptiveFormatVersion)
    throw FormatError(path + ": .tsp format version " + std::to_string(version) +
                      ", this tspplay reads versions " + std::to_string(kTspFormatVersion) +
                      " and " + std::to_string(kTspAdaptiveFormatVersion) +
                      " only; rebuild the file with this tspplay");
}

Aabb field_box(const Reader& r) {
  const auto dims = r.attr_numbers<int>(layout::kAttrDims, H5T_NATIVE_INT, 3);
  std::array<double, 3> org{0, 0, 0}, sp{1, 1, 1};
  if (r.has_attr(layout::kAttrOrigin) || r.has_attr(layout::kAttrSpacing)) {
    const auto o = r.attr_numbers<double>(layout::kAttrOrigin, H5T_NATIVE_DOUBLE, 3);
    const auto h = r.attr_numbers<double>(layout::kAttrSpacing, H5T_NATIVE_DOUBLE, 3);
    for (int a = 0; a < 3; ++a) {
      org[std::size_t(a)] = o[std::size_t(a)];
      sp[std::size_t(a)] = h[std::size_t(a)];
    }
    if (const std::string why = spacing_problem(org, sp); !why.empty())
      r.fail("attributes origin/spacing", "expected finite values and spacings that can be drawn: " + why);
  }
  Aabb b;
  for (int a = 0; a < 3; ++a) {
    if (dims[std::size_t(a)] < 1) r.fail("attribute dims", "expected sizes >= 1");
    b.lo[a] = org[std::size_t(a)];
    b.hi[a] = org[std::size_t(a)] + (dims[std::size_t(a)] - 1) * sp[std::size_t(a)];
  }
  return b;
}

}  // namespace tsp::detail
