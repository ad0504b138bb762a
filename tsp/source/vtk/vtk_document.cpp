#include "tsp/source/vtk/vtk_document.h"

#include <bit>
#include <cctype>
#include <charconv>
#include <cstring>
#include <limits>

#include "tsp/core/error.h"
#include "tsp/core/input_file.h"

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

std::string read_whole(const std::string& path, bool header_only) {
  InputFile in(path, "VTK file");
  std::string content;
  std::string chunk(kReadChunk, '\0');
  while (const std::size_t got = in.read(chunk.data(), chunk.size())) {
    content.append(chunk.data(), got);
    if (header_only && find_appended_start(content, path, false) != std::string::npos) break;
  }
  return content;
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

std::string array_where(const std::string& path, const pugi::xml_node& array) {
  std::string name = array.attribute("Name").value();
  return path + ", array " + (name.empty() ? std::string(array.parent().name()) : name);
}

bool is_float(vtkxml::ElemType t) {
  return t == vtkxml::ElemType::f32 || t == vtkxml::ElemType::f64;
}

// Whitespace-separated whole numbers into out; throws FormatError like parse_ascii.
void parse_ascii_integers(std::string_view text, std::span<std::int64_t> out,
                          const std::string& where) {
  std::size_t count = 0, i = 0;
  while (true) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    if (i >= text.size()) break;
    std::size_t end = i;
    while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end]))) ++end;
    std::int64_t v = 0;
    auto [ptr, ec] = std::from_chars(text.data() + i, text.data() + end, v);
    if (ec != std::errc() || ptr != text.data() + end)
      throw FormatError(where + ": ascii value \"" + std::string(text.substr(i, end - i)) +
                        "\" is not a whole number in the 64-bit range");
    if (count < out.size()) out[count] = v;
    ++count;
    i = end;
  }
  if (count != out.size())
    throw FormatError(where + ": ascii data holds " + std::to_string(count) + " values, expected " +
                      std::to_string(out.size()));
}

}  // namespace

pugi::xml_node find_data_array(const pugi::xml_node& section, const std::string& name) {
  for (pugi::xml_node a : section.children("DataArray"))
    if (name == a.attribute("Name").value()) return a;
  return {};
}

std::vector<std::string> data_array_names(const pugi::xml_node& section) {
  std::vector<std::string> names;
  for (pugi::xml_node a : section.children("DataArray"))
    names.push_back(a.attribute("Name").value());
  return names;
}

std::string join_names(const std::vector<std::string>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i];
  return v.empty() ? "none" : s;
}

VtkDocument::VtkDocument(const std::string& path, const std::string& type, bool header_only)
    : path_(path), header_only_(header_only) {
  content_ = read_whole(path, header_only);
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
  std::string found = root.attribute("type").value();
  if (found != type)
    throw FormatError(path + ": VTKFile type is \"" + found + "\", expected \"" + type + "\"");
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
  dataset_ = root.child(type.c_str());
  if (!dataset_) throw FormatError(path + ": no <" + type + "> element");
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

std::vector<unsigned char> VtkDocument::payload(const pugi::xml_node& array, std::uint64_t count,
                                                vtkxml::ElemType& type, std::string& ascii,
                                                std::uint64_t max_ratio) const {
  const std::string awhere = array_where(path_, array);
  type = vtkxml::parse_elem_type(array.attribute("type").value(), awhere);
  std::uint64_t bytes = 0;
  if (__builtin_mul_overflow(count, std::uint64_t(vtkxml::elem_size(type)), &bytes))
    throw FormatError(awhere + ": " + std::to_string(count) + " elements overflow a byte count");
  std::string format = array.attribute("format").value();
  if (format.empty() || format == "ascii") {
    ascii = array.text().get();
    // Every value takes a character and a separator: a count the text cannot hold is a lie.
    if (count > ascii.size() / 2 + 1)
      throw FormatError(awhere + ": expected " + std::to_string(count) +
                        " ascii values but the text holds only " + std::to_string(ascii.size()) +
                        " characters");
    return {};
  }
  if (format == "binary") {
    std::vector<unsigned char> raw = vtkxml::base64_decode(array.text().get(), awhere);
    return vtkxml::unpack_binary(raw, layout_, bytes, awhere, max_ratio);
  }
  if (format != "appended")
    throw FormatError(awhere + ": format \"" + format + "\", expected ascii, binary or appended");
  if (header_only_) throw FormatError(awhere + ": internal: appended data of a header-only read");
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
    return vtkxml::unpack_binary(raw, layout_, bytes, awhere, max_ratio);
  }
  std::span<const unsigned char> raw(
      reinterpret_cast<const unsigned char*>(content_.data()) + start, appended_end_ - start);
  return vtkxml::unpack_binary(raw, layout_, bytes, awhere, max_ratio);
}

std::vector<float> VtkDocument::floats(const pugi::xml_node& array, std::uint64_t count,
                                       std::uint64_t max_ratio) const {
  vtkxml::ElemType type;
  std::string ascii;
  std::vector<unsigned char> bytes = payload(array, count, type, ascii, max_ratio);
  std::vector<float> out(static_cast<std::size_t>(count));
  if (bytes.empty() && count > 0)
    vtkxml::parse_ascii(ascii, out, array_where(path_, array));
  else
    vtkxml::convert_to_float(bytes, type, layout_.big_endian, out);
  return out;
}

std::vector<std::int64_t> VtkDocument::integers(const pugi::xml_node& array,
                                                std::uint64_t count) const {
  vtkxml::ElemType type;
  std::string ascii;
  std::vector<unsigned char> bytes = payload(array, count, type, ascii);
  const std::string awhere = array_where(path_, array);
  if (is_float(type))
    throw FormatError(awhere + ": has type " + array.attribute("type").value() +
                      ", expected an integer type");
  std::vector<std::int64_t> out(static_cast<std::size_t>(count));
  if (bytes.empty() && count > 0) {
    parse_ascii_integers(ascii, out, awhere);
    return out;
  }
  vtkxml::convert_to_int64(bytes, type, layout_.big_endian, out, awhere);
  return out;
}

}  // namespace tsp::io
