// The STL reader driver (see fuzz/finding.h for the contract of drivers).
#pragma once

#include <cmath>
#include <string>
#include <string_view>

#include "fuzz/finding.h"
#include "geometry/mesh/stl_reader.h"

namespace vcpost::fuzz {

// Parses the bytes as STL (binary or ASCII, as the reader decides); the
// mesh must hold finite vertices and triangles that index them.
inline std::string run_stl(std::string_view bytes) {
  mesh::StlMesh mesh;
  try {
    mesh = mesh::parse_stl(bytes, "fuzz.stl");
  } catch (const mesh::StlError& e) {
    return std::string(e.id());
  }
  for (const auto& v : mesh.vertices) {
    if (!v.allFinite()) throw FuzzFinding("STL vertex not finite");
  }
  for (const auto& t : mesh.triangles) {
    for (auto i : t) {
      if (i >= mesh.vertices.size()) throw FuzzFinding("STL triangle index out of range");
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      throw FuzzFinding("degenerate STL triangle kept");
  }
  if (mesh.triangles.empty()) throw FuzzFinding("STL mesh without triangles accepted");
  return "ok";
}

}  // namespace vcpost::fuzz
