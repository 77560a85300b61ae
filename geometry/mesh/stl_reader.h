// STL reading (binary and ASCII) into an indexed triangle mesh.
//
// STL carries no unit: coordinates are multiplied by StlOptions::unit_mm
// (1 = the file is in mm, 25.4 = inches); everything returned is in mm.
// Binary vs ASCII is decided from the bytes, not the header text: a file
// whose size is exactly 84 + 50*n (n = the count at byte 80) is binary even
// when its header starts with "solid" (SolidWorks and others write that);
// otherwise a file starting with "solid" is read as ASCII.
//
// Errors are thrown as StlError with a code E46xx (core/error_codes.csv) and a
// message "<file>:<line>:<col>: error[E46xx]: ..." (ASCII) or
// "<file>: offset <byte>: error[E46xx]: ..." (binary).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace vcpost::mesh {

// Placed at a line and column (ASCII STL), at a byte offset (binary STL:
// "file: offset N: error[...]"), or at the file alone.
class StlError : public vcpost::Error {
 public:
  StlError(Code code, const SourceLocation& where, const std::string& message)
      : vcpost::Error(code, format_diagnostic(code, where, message), where) {}
  StlError(Code code, const std::string& file, std::uint64_t offset, const std::string& message)
      : vcpost::Error(
            code, format_diagnostic(code, {file + ": offset " + std::to_string(offset)}, message),
            {file}) {}
};

struct StlOptions {
  double unit_mm = 1.0;  // length of one file unit in mm (> 0)
};

enum class StlFormat { binary, ascii };

// An indexed triangle mesh: vertices welded where the file repeats exactly
// the same coordinates (STL stores each triangle's corners separately).
// Degenerate triangles (two equal corners or zero area) are dropped and
// counted; they touch nothing a ball could rest on alone.
struct StlMesh {
  std::vector<Eigen::Vector3d> vertices;                // mm
  std::vector<std::array<std::uint32_t, 3>> triangles;  // counterclockwise seen from outside
  StlFormat format = StlFormat::binary;
  std::string solid_name;  // ASCII "solid <name>", or the binary header text
  std::uint64_t degenerate_dropped = 0;
  std::uint64_t trailing_bytes = 0;  // binary: bytes after the last triangle (< 50: ignored)
};

// Parses STL bytes already in memory. file_name is used in messages only.
// Throws StlError (empty, truncated, bad_number, no_triangles, syntax, bad_unit).
StlMesh parse_stl(std::string_view bytes, const std::string& file_name,
                  const StlOptions& options = {});

// Reads a file and parses it. Throws StlError (also missing, unreadable).
StlMesh read_stl_file(const std::filesystem::path& path, const StlOptions& options = {});

// Writers, for tests and sample generation: the facet normal written is the
// right-handed normal of the corners (zero for a degenerate triangle).
// precision: significant digits of the ASCII numbers.
std::string to_ascii_stl(const StlMesh& mesh, const std::string& name, int precision = 17);
std::string to_binary_stl(const StlMesh& mesh, const std::string& header);

}  // namespace vcpost::mesh
