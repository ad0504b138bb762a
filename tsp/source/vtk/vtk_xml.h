// tsp/source/vtk: parsing of VTK XML files, independent of VolumeSource; may include core/.
// Decoding of VTK XML DataArray contents: ascii text, inline base64, appended raw or base64
// data, optional zlib block compression, any byte order, 8…64-bit integer and float types.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace tsp::io::vtkxml {

/// Element types of a DataArray's `type` attribute.
enum class ElemType { i8, u8, i16, u16, i32, u32, i64, u64, f32, f64 };

/// Parses a `type` attribute ("Int8" … "UInt64", "Float32", "Float64"); throws FormatError
/// naming `where` and the unknown name.
ElemType parse_elem_type(const std::string& name, const std::string& where);

/// Bytes per element.
int elem_size(ElemType t);

/// How a <VTKFile> encodes its binary data (byte_order, header_type, compressor).
struct BinaryLayout {
  bool big_endian = false;  ///< byte_order="BigEndian"
  bool header64 = false;    ///< header_type="UInt64" (default UInt32)
  bool zlib = false;        ///< compressor="vtkZLibDataCompressor"
};

/// Decodes base64 text, skipping whitespace and accepting '=' padding between separately
/// encoded parts (VTK encodes the header and the data as two base64 runs). Throws
/// FormatError naming `where` on a character outside the base64 alphabet.
std::vector<unsigned char> base64_decode(std::string_view text, const std::string& where);

/// Deflate cannot expand data by more than about 1032:1; a zlib header claiming more lies.
inline constexpr std::uint64_t kMaxInflateRatio = 1032;

/// Unpacks one binary DataArray that starts at bytes[0] with its UInt32/UInt64 header:
/// uncompressed [nbytes][data] or zlib [nblocks][blocksize][lastsize][csize…][blocks…].
/// Returns exactly expected_bytes of data. Throws FormatError naming `where` when the header
/// disagrees with expected_bytes, the bytes are truncated, a block does not inflate, or zlib
/// data would inflate more than max_ratio:1 over its compressed blocks (checked from the
/// header, before anything is allocated or inflated).
std::vector<unsigned char> unpack_binary(std::span<const unsigned char> bytes,
                                         const BinaryLayout& layout, std::uint64_t expected_bytes,
                                         const std::string& where,
                                         std::uint64_t max_ratio = kMaxInflateRatio);

/// Converts out.size() elements of type t stored in bytes (file byte order) to floats.
/// Values outside the float range become ±inf. Never throws; bytes must hold them all.
void convert_to_float(std::span<const unsigned char> bytes, ElemType t, bool big_endian,
                      std::span<float> out);

/// Converts out.size() integer elements of type t (not f32/f64) to int64 exactly. Throws
/// FormatError naming `where` when a UInt64 value exceeds the int64 range.
void convert_to_int64(std::span<const unsigned char> bytes, ElemType t, bool big_endian,
                      std::span<std::int64_t> out, const std::string& where);

/// Parses whitespace-separated numbers (ascii format) into out; throws FormatError naming
/// `where` when a token is not a number or the count differs from out.size().
void parse_ascii(std::string_view text, std::span<float> out, const std::string& where);

/// Parses an extent "x0 x1 y0 y1 z0 z1" (32-bit integers, lo <= hi per axis) into out. Throws
/// FormatError naming where and what (the attribute: "WholeExtent", "Extent").
void parse_extent(const char* text, long long out[6], const std::string& where, const char* what);

}  // namespace tsp::io::vtkxml
