// STL reading (binary and ASCII) into an indexed triangle mesh.
//
// STL carries no unit: coordinates are multiplied by StlOptions::unit_mm
// (1 = the file is in mm, 25.4 = inches); everything returned is in mm.
// Binary vs ASCII is decided from the bytes, not the header text: a file
// whose size is exactly 84 + 50*n (n = the count at byte 80) is binary even
// when its header starts with "solid" (SolidWorks and others write that);
// otherwise a file starting with "solid" is read as ASCII.
//
// Errors are thrown as StlError with a stable code (table below) and a
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

// Stable codes; never renumber.
enum class StlCode : std::uint16_t {
  missing = 4601,         // the file does not exist
  unreadable = 4602,      // exists but cannot be read (permissions, a directory)
  empty = 4603,           // zero bytes
  truncated = 4604,       // binary shorter than its triangle count says; ASCII without endsolid
  bad_number = 4605,      // NaN, infinity or not a number in a coordinate
  no_triangles = 4606,    // a valid file with no (non-degenerate) triangle
  syntax = 4607,          // ASCII: a keyword other than the one expected
  bad_unit = 4608,        // unit_mm not a positive finite number
  count_mismatch = 4609,  // binary: whole triangles past the count (the count is wrong)
};

// "E4604"
std::string code_id(StlCode code);

// Placed at a line and column (ASCII STL), at a byte offset (binary STL:
// "file: offset N: error[...]"), or at the file alone.
class StlError : public vcpost::Error {
 public:
  StlError(StlCode code, const SourceLocation& where, const std::string& message)
      : vcpost::Error(code_id(code), format_diagnostic(code_id(code), where, message), where),
        code_(code) {}
  StlError(StlCode code, const std::string& file, std::uint64_t offset, const std::string& message)
      : vcpost::Error(code_id(code),
                      format_diagnostic(code_id(code),
                                        {file + ": offset " + std::to_string(offset)}, message),
                      {file}),
        code_(code) {}
  StlCode code() const { return code_; }

 private:
  StlCode code_;
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
