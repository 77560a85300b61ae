// What a BrepModel holds, for the files that build it (brep_build.cpp),
// trim its faces (brep_trim.cpp) and answer its queries (brep_query.cpp):
// each face's surface, trim and tessellation, the edges, the box trees.
// Includes OpenCASCADE: for geometry/occt/ only.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Geom2d_Curve.hxx>
#include <Geom_Curve.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Face.hxx>
#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/occt/box_tree.h"
#include "geometry/occt/brep_model.h"
#include "geometry/occt/surface_eval.h"

namespace vcpost::occt {

struct EdgeData {
  Handle(Geom_Curve) curve;
  bool closed = false;  // starts and ends at one vertex (a full circle): its ends are no corner
  double t0 = 0, t1 = 0;
  std::vector<double> ts;  // samples for the start of Newton's method
  std::vector<Eigen::Vector3d> points;
  Eigen::AlignedBox3d box;  // of the samples, grown by the chord error bound
};

struct FaceEdge {
  int edge = 0;
  Handle(Geom2d_Curve) pcurve;
};

enum class Trim : std::uint8_t { outside, inside, boundary };

struct FaceData {
  FaceData(TopoDS_Face f, SurfaceEval e) : face(std::move(f)), eval(std::move(e)) {}
  TopoDS_Face face;
  SurfaceEval eval;
  bool reversed = false;
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  double u_period = 0, v_period = 0;        // > 0 when the surface is periodic in that direction
  bool u_closed = false, v_closed = false;  // the face spans the whole period: no bound there
  bool natural = false;                     // the trim is the whole (u,v) box
  static constexpr int kGrid = 32;
  std::vector<Trim> cells;  // kGrid x kGrid classification of the (u,v) box
  std::vector<std::array<Eigen::Vector2d, 2>> loops;  // segments of the trim polygon in (u,v)
  double polygon_error = 0;  // largest chord error of those segments, in (u,v)
  // Where the grid says "boundary": the segments whose v range meets each
  // grid row (the crossing count of a ray along +u needs no others) and the
  // segments within one cell of each cell (the only ones that can be
  // within the chord-error band of a point in it). local_lists is false
  // when the band is wider than a cell; then every segment is read.
  bool local_lists = false;
  std::vector<std::uint32_t> row_start, row_segments;
  std::vector<std::uint32_t> cell_start, cell_segments;
  std::vector<std::array<Eigen::Vector3d, 3>> triangles;
  std::vector<std::array<Eigen::Vector2d, 3>> triangle_uv;
  BoxTree tree;
  std::vector<FaceEdge> edges;
  double slack = 0;  // bound on the tessellation's distance from the face, mm
  Eigen::AlignedBox3d box;
};

// Closest point of triangle abc to p, as barycentric weights (wa, wb, wc).
inline Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                           const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double t = d1 / (d1 - d3);
    return {1 - t, t, 0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    return {1 - t, 0, t};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - t, t};
  }
  const double inv = 1 / (va + vb + vc);
  return {1 - (vb + vc) * inv, vb * inv, vc * inv};
}

// The trim (brep_trim.cpp). add_trims: the trim polygon (f.loops,
// f.polygon_error) and the face's edges (f.edges); returns the number of
// wires. classify_trim: whether the trim is the (u,v) box (f.natural); else
// the grid of cells inside, outside or on the trim, and the segments near
// each row and cell. classify: where (u,v) lies, the grid first, then the
// polygon, then (within the polygon's chord error) the exact pcurves.
int add_trims(FaceData& f, const TopoDS_Face& face, const TopTools_IndexedMapOfShape& edge_map);
void classify_trim(FaceData& f, int wires);
Trim classify(const FaceData& f, const Eigen::Vector2d& uv);

// A local minimum of the distance on a face's surface (Newton's method).
struct Local {
  Eigen::Vector2d uv;
  SurfacePoint s;
  bool on_box_bound = false;
};

struct BrepModel::Impl {
  std::vector<FaceData> faces;
  std::vector<EdgeData> edges;
  BoxTree face_tree;
  double max_slack = 0;
  StepInfo info;
  Eigen::AlignedBox3d bounds;

  // The queries (brep_query.cpp).
  std::optional<geometry::ModelContact> query(const Eigen::Vector3d& p, double max_distance,
                                              geometry::ContactHint* hint) const;

  // Brings (u,v) into the face's box: periodic directions wrap to the
  // period centred on the box, then every direction clamps.
  Eigen::Vector2d into_box(const FaceData& f, Eigen::Vector2d uv, bool& clamped) const;
  static bool at_bound(const FaceData& f, const Eigen::Vector2d& uv);
  // Newton's method for the closest point of the face's surface, inside
  // its (u,v) box; a variable on the box bound with the gradient pointing
  // out stays fixed. Empty when it does not converge.
  std::optional<Local> newton(const FaceData& f, const Eigen::Vector3d& p,
                              Eigen::Vector2d uv) const;
  // curvature: whether to fill ModelContact::curvature (only reports read it).
  geometry::ModelContact make_contact(int face, const Eigen::Vector3d& p, const Eigen::Vector2d& uv,
                                      const SurfacePoint& s, geometry::ContactType type,
                                      const Eigen::Vector3d& point, bool curvature) const;
  // Closest point of the face's boundary edges (seams and degenerate edges
  // excluded), nearer than `bound`.
  std::optional<geometry::ModelContact> on_edges(int face, const Eigen::Vector3d& p, double bound,
                                                 bool curvature) const;
  // The exact closest point of one face from a start (u,v): Newton on the
  // surface, then the trim; outside it, the face's edges.
  std::optional<geometry::ModelContact> refine(int face, const Eigen::Vector3d& p,
                                               const Eigen::Vector2d& start, double bound,
                                               bool curvature) const;
  // A contact inside a face; where the parametrisation is singular (a
  // pole: first fundamental form degenerate) normal and curvatures come
  // from a point a hair inside the (u,v) box.
  geometry::ModelContact face_contact(int face, const Eigen::Vector3d& p, const Eigen::Vector2d& uv,
                                      const SurfacePoint& s, bool curvature) const;
  // Nearest tessellation triangle of a face within `bound`: its distance
  // and the (u,v) of its closest point.
  std::optional<std::pair<double, Eigen::Vector2d>> nearest_triangle(const FaceData& f,
                                                                     const Eigen::Vector3d& p,
                                                                     double bound) const;
};

}  // namespace vcpost::occt
