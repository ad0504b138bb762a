// One VTK XML file (.vti, .vtu, …) read into memory: the parsed document up to its appended
// block, the file's binary layout, and decoding of any DataArray into floats or integers with
// the size checks done before anything is allocated. VtiFile and VtuFile are built on it.
#pragma once
#include <cstdint>
#include <memory>
#include <pugixml.hpp>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "tsp/source/vtk/vtk_xml.h"

namespace tsp::io {

/// A parsed VTK XML file of one dataset type. Header-only documents skip the appended binary
/// block (enough for the grid and the array list, cheap for big files) and cannot decode it.
class VtkDocument {
 public:
  /// Reads and parses path, whose VTKFile type must be `type` ("ImageData", "UnstructuredGrid").
  /// Throws IoError (missing/unreadable) or FormatError (not well-formed XML, another type,
  /// unsupported byte order, header type, compressor or appended encoding).
  VtkDocument(const std::string& path, const std::string& type, bool header_only);

  /// The file's path.
  const std::string& path() const { return path_; }
  /// The dataset element (<ImageData>, <UnstructuredGrid>), never null.
  pugi::xml_node dataset() const { return dataset_; }
  /// How the binary data is encoded.
  const vtkxml::BinaryLayout& layout() const { return layout_; }

  /// Decodes `count` elements of array (ascii, inline base64 or appended) into floats. Checks
  /// that the file can hold count elements before allocating (zlib data: at most max_ratio:1
  /// over its compressed blocks); throws FormatError naming the file and the array on
  /// truncated, corrupt or mis-sized data.
  std::vector<float> floats(const pugi::xml_node& array, std::uint64_t count,
                            std::uint64_t max_ratio = vtkxml::kMaxInflateRatio) const;
  /// Decodes `count` integer elements of array exactly (as int64); throws like floats(), and
  /// when the array's type is a float type or an unsigned value exceeds the int64 range.
  std::vector<std::int64_t> integers(const pugi::xml_node& array, std::uint64_t count) const;

 private:
  std::vector<unsigned char> payload(const pugi::xml_node& array, std::uint64_t count,
                                     vtkxml::ElemType& type, std::string& ascii,
                                     std::uint64_t max_ratio = vtkxml::kMaxInflateRatio) const;

  std::string path_;
  std::string content_;  // file bytes (up to the appended block when header-only)
  std::unique_ptr<pugi::xml_document> doc_;
  pugi::xml_node dataset_;
  vtkxml::BinaryLayout layout_;
  bool header_only_ = false;
  std::size_t appended_ = std::string::npos;      // first appended byte in content_
  std::size_t appended_end_ = std::string::npos;  // end of the appended block
  bool appended_base64_ = false;
  std::set<unsigned long long> appended_offsets_;  // every array's offset, to bound base64 runs
};

/// The DataArray children of section (PointData, CellData, Cells…) by name; null when absent.
pugi::xml_node find_data_array(const pugi::xml_node& section, const std::string& name);
/// Names of section's DataArray children, in file order.
std::vector<std::string> data_array_names(const pugi::xml_node& section);
/// "a, b, c" ("none" for an empty list).
std::string join_names(const std::vector<std::string>& names);

}  // namespace tsp::io
