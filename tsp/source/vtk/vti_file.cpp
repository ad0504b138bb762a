#include "tsp/source/vtk/vti_file.h"

#include <algorithm>
#include <cassert>
#include <cctype>
#include <charconv>
#include <climits>
#include <cstdint>
#include <fstream>
#include <sstream>

#include "tsp/core/error.h"

namespace tsp::io {
namespace {

constexpr std::size_t kReadChunk = std::size_t(1) << 20;
const char* const kAppendedTag = "<AppendedData";

// Position of the first appended byte (after the '_' marker) or npos when the block (or its
// marker) is not in content yet; throws when the block is there but malformed.
std::size_t find_appended_start(const std::string& content, const std::string& path,
                                bool complete) {
  std::size_t tag = content.find(kAppendedTag);
  if (tag == std::string::npos) return std::string::npos;
  std::size_t close = content.find('>', tag);
  if (close == std::string::npos) {
    if (complete) throw FormatError(path + ": <AppendedData> tag is not closed");
    return std::string::npos;
  }
  std::size_t i = close + 1;
  while (i < content.size() && std::isspace(static_cast<unsigned char>(content[i]))) ++i;
  if (i >= content.size()) {
    if (complete) throw FormatError(path + ": <AppendedData> block is empty, expected '_' + data");
    return std::string::npos;
  }
  if (content[i] != '_')
    throw FormatError(path + ": <AppendedData> block starts with '" + std::string(1, content[i]) +
                      "', expected the '_' marker");
  return i + 1;
}

std::string read_file(const std::string& path, bool header_only) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot be opened for reading");
  std::string content;
  std::string chunk(kReadChunk, '\0');
  while (in) {
    in.read(chunk.data(), std::streamsize(chunk.size()));
    content.append(chunk.data(), std::size_t(in.gcount()));
    if (header_only && find_appended_start(content, path, false) != std::string::npos) break;
  }
  if (in.bad()) throw IoError(path + ": read error");
  return content;
}

// Parses "x0 x1 y0 y1 z0 z1".
void parse_extent(const char* text, long long out[6], const std::string& where, const char* what) {
  std::istringstream in(text ? text : "");
  for (int i = 0; i < 6; ++i)
    if (!(in >> out[i]))
      throw FormatError(where + ": " + what + " \"" + (text ? text : "") + "\" is not 6 integers");
  std::string rest;
  if (in >> rest) throw FormatError(where + ": " + what + " has more than 6 values");
  for (int i = 0; i < 6; ++i)
    if (out[i] < INT32_MIN || out[i] > INT32_MAX)
      throw FormatError(where + ": " + what + " value " + std::to_string(out[i]) +
                        " is outside the 32-bit range");
  for (int a = 0; a < 3; ++a)
    if (out[2 * a + 1] < out[2 * a])
      throw FormatError(where + ": " + what + " axis " + std::to_string(a) + " is [" +
                        std::to_string(out[2 * a]) + ", " + std::to_string(out[2 * a + 1]) +
                        "], expected lo <= hi");
}

std::vector<std::string> array_names(const pugi::xml_node& section) {
  std::vector<std::string> names;
  for (pugi::xml_node a : section.children("DataArray"))
    names.push_back(a.attribute("Name").value());
  return names;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i];
  return v.empty() ? "none" : s;
}

pugi::xml_node find_array(const pugi::xml_node& section, const std::string& name) {
  for (pugi::xml_node a : section.children("DataArray"))
    if (name == a.attribute("Name").value()) return a;
  return {};
}

// An appended DataArray's offset: a whole non-negative decimal number. Throws FormatError.
unsigned long long appended_offset(const pugi::xml_node& array, const std::string& where) {
  const std::string text = array.attribute("offset").value();
  unsigned long long v = 0;
  const char* end = text.data() + text.size();
  auto [p, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || ec != std::errc() || p != end)
    throw FormatError(where + ": appended offset \"" + text +
                      "\" is not a non-negative whole number");
  return v;
}

// Every appended DataArray's offset, walking the tree without recursion (a file may nest
// elements tens of thousands deep).
void collect_appended_offsets(const pugi::xml_node& root, std::set<unsigned long long>& out,
                              const std::string& where) {
  pugi::xml_node n = root.first_child();
  while (n && n != root) {
    if (std::string(n.name()) == "DataArray" &&
        std::string(n.attribute("format").value()) == "appended" && n.attribute("offset"))
      out.insert(appended_offset(n, where + ", array " + n.attribute("Name").value()));
    if (n.first_child()) {
      n = n.first_child();
      continue;
    }
    while (n && n != root && !n.next_sibling()) n = n.parent();
    if (n && n != root) n = n.next_sibling();
  }
}

}  // namespace

VtiFile::VtiFile(const std::string& path, bool header_only)
    : path_(path), header_only_(header_only) {
  content_ = read_file(path, header_only);
  doc_ = std::make_unique<pugi::xml_document>();
  appended_ = find_appended_start(content_, path, !header_only);
  pugi::xml_parse_result res;
  if (appended_ != std::string::npos) {
    // Binary appended data is not XML: parse the text before it, closing the open elements.
    std::string head = content_.substr(0, content_.rfind('>', appended_) + 1);
    head += "</AppendedData></VTKFile>";
    res = doc_->load_buffer(head.data(), head.size());
  } else {
    res = doc_->load_buffer(content_.data(), content_.size());
    content_.clear();  // inline data lives in the parsed document now
    content_.shrink_to_fit();
  }
  if (!res)
    throw FormatError(path + ": not well-formed XML (" + res.description() + " at byte " +
                      std::to_string(res.offset) + ")");
  pugi::xml_node root = doc_->child("VTKFile");
  if (!root) throw FormatError(path + ": no <VTKFile> root element, expected a VTK XML file");
  std::string type = root.attribute("type").value();
  if (type != "ImageData")
    throw FormatError(path + ": VTKFile type is \"" + type + "\", expected \"ImageData\"");
  std::string order = root.attribute("byte_order").value();
  if (order == "BigEndian") {
    layout_.big_endian = true;
  } else if (!order.empty() && order != "LittleEndian") {
    throw FormatError(path + ": byte_order \"" + order + "\", expected LittleEndian or BigEndian");
  }
  std::string header = root.attribute("header_type").value();
  if (header == "UInt64") {
    layout_.header64 = true;
  } else if (!header.empty() && header != "UInt32") {
    throw FormatError(path + ": header_type \"" + header + "\", expected UInt32 or UInt64");
  }
  std::string compressor = root.attribute("compressor").value();
  if (compressor == "vtkZLibDataCompressor") {
    layout_.zlib = true;
  } else if (!compressor.empty()) {
    throw FormatError(path + ": compressor \"" + compressor +
                      "\" is not supported, expected none or vtkZLibDataCompressor");
  }
  image_ = root.child("ImageData");
  if (!image_) throw FormatError(path + ": no <ImageData> element");
  parse_extent(image_.attribute("WholeExtent").value(), whole_, path, "WholeExtent");
  if (!image_.child("Piece")) throw FormatError(path + ": <ImageData> has no <Piece>");
  if (appended_ != std::string::npos) {
    std::string enc = root.child("AppendedData").attribute("encoding").value();
    if (enc == "base64") {
      appended_base64_ = true;
    } else if (enc != "raw") {
      throw FormatError(path + ": AppendedData encoding \"" + enc + "\", expected raw or base64");
    }
    appended_end_ = appended_base64_
                        ? std::min(content_.find("</AppendedData>", appended_), content_.size())
                        : content_.size();
    collect_appended_offsets(root, appended_offsets_, path);
  }
}

VtiField VtiFile::resolve(const std::string& requested) const {
  pugi::xml_node piece = image_.child("Piece");
  std::vector<std::string> points = array_names(piece.child("PointData"));
  std::vector<std::string> cells = array_names(piece.child("CellData"));
  const std::string listing = "PointData: " + join(points) + "; CellData: " + join(cells);
  VtiField f;
  if (requested.empty()) {
    std::string scalars = piece.child("PointData").attribute("Scalars").value();
    if (points.size() == 1) {
      f.name = points[0];
    } else if (points.empty() && cells.size() == 1) {
      f = {cells[0], true};
    } else if (!scalars.empty() && std::count(points.begin(), points.end(), scalars)) {
      f.name = scalars;
    } else {
      throw FormatError(path_ + ": no field given and no single array to default to (" + listing +
                        "); name one with --field");
    }
  } else if (std::count(points.begin(), points.end(), requested)) {
    f.name = requested;
  } else if (std::count(cells.begin(), cells.end(), requested)) {
    f = {requested, true};
  } else {
    throw FormatError(path_ + ": field '" + requested +
                      "' not found; available arrays: " + listing);
  }
  pugi::xml_node array = find_array(piece.child(f.cells ? "CellData" : "PointData"), f.name);
  int comps = array.attribute("NumberOfComponents").as_int(1);
  if (comps != 1)
    throw FormatError(path_ + ": field " + f.name + " has " + std::to_string(comps) +
                      " components; a scalar field is expected");
  return f;
}

Dims VtiFile::dims(const VtiField& f) const {
  long long n[3];
  for (int a = 0; a < 3; ++a) {
    const long long len = whole_[2 * a + 1] - whole_[2 * a];  // both within 32 bits
    n[a] = f.cells ? std::max(len, 1LL) : len + 1;
  }
  check_grid(n[0], n[1], n[2], 1, path_ + ", WholeExtent");
  return Dims{int(n[0]), int(n[1]), int(n[2])};
}

void VtiFile::read(const VtiField& f, std::span<float> out) const {
  assert(!header_only_);
  const Dims d = dims(f);
  assert(std::int64_t(out.size()) == d.count());
  std::vector<unsigned char> covered(out.size(), 0);
  int index = 0;
  for (pugi::xml_node piece : image_.children("Piece")) {
    const std::string pwhere = path_ + ", piece " + std::to_string(index++);
    long long e[6];
    parse_extent(piece.attribute("Extent").value(), e, pwhere, "Extent");
    std::int64_t lo[3], n[3];
    for (int a = 0; a < 3; ++a) {
      if (e[2 * a] < whole_[2 * a] || e[2 * a + 1] > whole_[2 * a + 1])
        throw FormatError(pwhere + ": Extent lies outside WholeExtent");
      const bool flat = whole_[2 * a + 1] == whole_[2 * a];
      lo[a] = e[2 * a] - whole_[2 * a];
      n[a] = f.cells ? (flat ? 1 : e[2 * a + 1] - e[2 * a]) : e[2 * a + 1] - e[2 * a] + 1;
    }
    pugi::xml_node array = find_array(piece.child(f.cells ? "CellData" : "PointData"), f.name);
    if (!array)
      throw FormatError(pwhere + ": has no " + (f.cells ? "CellData" : "PointData") + " array '" +
                        f.name + "'");
    int comps = array.attribute("NumberOfComponents").as_int(1);
    if (comps != 1)
      throw FormatError(pwhere + ": field " + f.name + " has " + std::to_string(comps) +
                        " components; a scalar field is expected");
    std::vector<float> buf(static_cast<std::size_t>(n[0] * n[1] * n[2]));
    decode(array, buf);
    for (std::int64_t z = 0; z < n[2]; ++z)
      for (std::int64_t y = 0; y < n[1]; ++y)
        for (std::int64_t x = 0; x < n[0]; ++x) {
          std::size_t dst = std::size_t(((lo[2] + z) * d.y + lo[1] + y) * d.x + lo[0] + x);
          out[dst] = buf[std::size_t((z * n[1] + y) * n[0] + x)];
          covered[dst] = 1;
        }
  }
  auto gap = std::find(covered.begin(), covered.end(), 0);
  if (gap != covered.end()) {
    std::size_t i = std::size_t(gap - covered.begin());
    throw FormatError(path_ + ": the pieces do not cover WholeExtent (sample " +
                      std::to_string(i % d.x) + "," + std::to_string(i / d.x % d.y) + "," +
                      std::to_string(i / d.x / d.y) + " of field " + f.name + " is missing)");
  }
}

void VtiFile::decode(const pugi::xml_node& array, std::span<float> out) const {
  const std::string awhere = path_ + ", array " + array.attribute("Name").value();
  vtkxml::ElemType type = vtkxml::parse_elem_type(array.attribute("type").value(), awhere);
  const std::uint64_t bytes = std::uint64_t(out.size()) * vtkxml::elem_size(type);
  std::string format = array.attribute("format").value();
  if (format.empty() || format == "ascii") {
    vtkxml::parse_ascii(array.text().get(), out, awhere);
    return;
  }
  std::vector<unsigned char> payload;
  if (format == "binary") {
    std::vector<unsigned char> raw = vtkxml::base64_decode(array.text().get(), awhere);
    payload = vtkxml::unpack_binary(raw, layout_, bytes, awhere);
  } else if (format == "appended") {
    if (appended_ == std::string::npos)
      throw FormatError(awhere + ": format=\"appended\" but the file has no <AppendedData>");
    if (!array.attribute("offset"))
      throw FormatError(awhere + ": format=\"appended\" without an offset attribute");
    const unsigned long long offset = appended_offset(array, awhere);
    if (offset > appended_end_ - appended_)
      throw FormatError(awhere + ": appended offset " + std::to_string(offset) +
                        " lies beyond the end of the file (truncated?)");
    const std::size_t start = appended_ + std::size_t(offset);
    if (appended_base64_) {
      auto next = appended_offsets_.upper_bound(offset);
      std::size_t end = next == appended_offsets_.end()
                            ? appended_end_
                            : std::min(appended_end_, appended_ + std::size_t(*next));
      std::vector<unsigned char> raw =
          vtkxml::base64_decode(std::string_view(content_).substr(start, end - start), awhere);
      payload = vtkxml::unpack_binary(raw, layout_, bytes, awhere);
    } else {
      std::span<const unsigned char> raw(
          reinterpret_cast<const unsigned char*>(content_.data()) + start, appended_end_ - start);
      payload = vtkxml::unpack_binary(raw, layout_, bytes, awhere);
    }
  } else {
    throw FormatError(awhere + ": format \"" + format + "\", expected ascii, binary or appended");
  }
  vtkxml::convert_to_float(payload, type, layout_.big_endian, out);
}

}  // namespace tsp::io
