// A BrepModel built from a shape: each face's surface evaluator, trim,
// tessellation (with a bound on its distance from the face) and box tree,
// the edges sampled for the edge search, and the tree over the faces.
#include <BRepBndLib.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Poly_Triangulation.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Vertex.hxx>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "geometry/occt/brep_faces.h"
#include "geometry/occt/shape_model.h"

namespace vcpost::occt {

using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

// Tessellation (with (u,v) at the nodes) or, without one, a (u,v) grid;
// f.slack bounds the surface's distance from the triangles.
void tessellate(FaceData& f, const TopoDS_Face& face) {
  const double span_u = f.u1 - f.u0, span_v = f.v1 - f.v0;
  TopLoc_Location location;
  const Handle(Poly_Triangulation) mesh = BRep_Tool::Triangulation(face, location);
  if (!mesh.IsNull() && mesh->HasUVNodes() && mesh->NbTriangles() > 0) {
    const gp_Trsf trsf = location.Transformation();
    for (int t = 1; t <= mesh->NbTriangles(); ++t) {
      int n[3];
      mesh->Triangle(t).Get(n[0], n[1], n[2]);
      std::array<Vector3d, 3> tri;
      std::array<Vector2d, 3> uv;
      for (int k = 0; k < 3; ++k) {
        tri[k] = to_eigen(mesh->Node(n[k]).Transformed(trsf).XYZ());
        const gp_Pnt2d q = mesh->UVNode(n[k]);
        uv[k] = {q.X(), q.Y()};
      }
      f.triangles.push_back(tri);
      f.triangle_uv.push_back(uv);
    }
    // The triangulation's own Deflection() is not a bound we can use, so
    // measure how far the surface at each triangle's (u,v) centre and edge
    // midpoints lies from the triangle.
    double chord = 0;
    for (std::size_t t = 0; t < f.triangles.size(); ++t) {
      const auto& tri = f.triangles[t];
      const auto& uv = f.triangle_uv[t];
      const auto gap = [&](const Vector2d& q) {
        const Vector3d x = f.eval.d2(q.x(), q.y()).p;
        const Vector3d w = closest_on_triangle(x, tri[0], tri[1], tri[2]);
        chord = std::max(chord, (w.x() * tri[0] + w.y() * tri[1] + w.z() * tri[2] - x).norm());
      };
      gap((uv[0] + uv[1] + uv[2]) / 3);
      for (int k = 0; k < 3; ++k) gap((uv[k] + uv[(k + 1) % 3]) / 2);
    }
    f.slack = 2 * chord + 1e-6;
  } else {
    constexpr int g = 24;
    std::vector<Vector3d> grid;
    for (int i = 0; i <= g; ++i) {
      for (int j = 0; j <= g; ++j) {
        grid.push_back(f.eval.d2(f.u0 + span_u * i / g, f.v0 + span_v * j / g).p);
      }
    }
    double chord = 0;
    for (int i = 0; i < g; ++i) {
      for (int j = 0; j < g; ++j) {
        const auto at = [&](int a, int b) { return grid_index(a, g + 1, b); };
        const auto uv = [&](int a, int b) {
          return Vector2d(f.u0 + span_u * a / g, f.v0 + span_v * b / g);
        };
        f.triangles.push_back({grid[at(i, j)], grid[at(i + 1, j)], grid[at(i + 1, j + 1)]});
        f.triangle_uv.push_back({uv(i, j), uv(i + 1, j), uv(i + 1, j + 1)});
        f.triangles.push_back({grid[at(i, j)], grid[at(i + 1, j + 1)], grid[at(i, j + 1)]});
        f.triangle_uv.push_back({uv(i, j), uv(i + 1, j + 1), uv(i, j + 1)});
        const Vector3d mid =
            f.eval.d2(f.u0 + span_u * (i + 0.5) / g, f.v0 + span_v * (j + 0.5) / g).p;
        chord = std::max(chord, (mid - (grid[at(i, j)] + grid[at(i + 1, j + 1)]) / 2).norm());
      }
    }
    f.slack = 4 * chord + 1e-6;
  }
}

// The box tree over the triangles and the face's box grown by the slack.
void build_box_tree(FaceData& f) {
  std::vector<Eigen::AlignedBox3d> boxes;
  boxes.reserve(f.triangles.size());
  for (const auto& tri : f.triangles) {
    Eigen::AlignedBox3d b(tri[0]);
    b.extend(tri[1]);
    b.extend(tri[2]);
    boxes.push_back(b);
    f.box.extend(b);
  }
  f.tree = BoxTree(boxes);
  const Vector3d grow = Vector3d::Constant(f.slack);
  f.box = Eigen::AlignedBox3d(f.box.min() - grow, f.box.max() + grow);
}

// Flips f.reversed where the face's area-weighted mean normal points down.
void orient_up_normal(FaceData& f) {
  // Area-weighted mean of the oriented normal over the tessellation.
  double up = 0;
  for (std::size_t t = 0; t < f.triangles.size(); ++t) {
    const auto& tri = f.triangles[t];
    const auto& uv = f.triangle_uv[t];
    const Vector2d c = (uv[0] + uv[1] + uv[2]) / 3;
    const SurfacePoint sp = f.eval.d2(c.x(), c.y());
    const Vector3d n = sp.su.cross(sp.sv);
    const double area = (tri[1] - tri[0]).cross(tri[2] - tri[0]).norm();
    if (n.norm() > 0) up += area * n.z() / n.norm();
  }
  if ((f.reversed ? -up : up) < 0) f.reversed = !f.reversed;
}

void add_face(BrepModel::Impl& model, const TopoDS_Face& face,
              const TopTools_IndexedMapOfShape& edge_map, bool orient_up) {
  Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
  if (surface.IsNull()) return;
  FaceData f(face, SurfaceEval(surface));
  f.reversed = face.Orientation() == TopAbs_REVERSED;
  BRepTools::UVBounds(face, f.u0, f.u1, f.v0, f.v1);
  if (surface->IsUPeriodic()) f.u_period = surface->UPeriod();
  if (surface->IsVPeriodic()) f.v_period = surface->VPeriod();
  const int wires = add_trims(f, face, edge_map);
  const double span_u = f.u1 - f.u0, span_v = f.v1 - f.v0;
  if (!(span_u > 0 && span_v > 0)) return;
  f.u_closed = f.u_period > 0 && span_u >= f.u_period * (1 - 1e-9);
  f.v_closed = f.v_period > 0 && span_v >= f.v_period * (1 - 1e-9);
  classify_trim(f, wires);
  tessellate(f, face);
  build_box_tree(f);
  if (orient_up) orient_up_normal(f);
  model.faces.push_back(std::move(f));
}

void add_edges(BrepModel::Impl& model, const TopTools_IndexedMapOfShape& edge_map) {
  model.edges.resize(static_cast<std::size_t>(edge_map.Extent()));
  for (int i = 1; i <= edge_map.Extent(); ++i) {
    const TopoDS_Edge& edge = TopoDS::Edge(edge_map(i));
    EdgeData& e = model.edges[static_cast<std::size_t>(i - 1)];
    if (BRep_Tool::Degenerated(edge)) continue;
    e.curve = BRep_Tool::Curve(edge, e.t0, e.t1);
    if (e.curve.IsNull()) continue;
    TopoDS_Vertex first, last;
    TopExp::Vertices(edge, first, last);
    e.closed = !first.IsNull() && first.IsSame(last);
    constexpr int kSamples = 64;
    double chord = 0;
    for (int k = 0; k <= kSamples; ++k) {
      const double t = e.t0 + (e.t1 - e.t0) * k / kSamples;
      e.ts.push_back(t);
      e.points.push_back(to_eigen(e.curve->Value(t).XYZ()));
      e.box.extend(e.points.back());
      if (k > 0) {
        const Vector3d mid = to_eigen(e.curve->Value(t - (e.t1 - e.t0) / kSamples / 2).XYZ());
        chord = std::max(chord, (mid - (e.points[k - 1] + e.points[k]) / 2).norm());
      }
    }
    const Vector3d grow = Vector3d::Constant(4 * chord + 1e-6);
    e.box = Eigen::AlignedBox3d(e.box.min() - grow, e.box.max() + grow);
  }
}

}  // namespace

BrepModel model_from_shape(const TopoDS_Shape& shape, const BrepOptions& options,
                           const std::string& source, const std::string& length_unit) {
  auto impl = std::make_unique<BrepModel::Impl>();
  impl->info.length_unit = length_unit;
  try {
    TopTools_IndexedMapOfShape face_map, edge_map;
    TopExp::MapShapes(shape, TopAbs_FACE, face_map);
    TopExp::MapShapes(shape, TopAbs_EDGE, edge_map);
    if (face_map.Extent() == 0) {
      throw ModelError(Code::E4105, source,
                       "the model holds no faces (points, curves or an empty assembly only); "
                       "export the finished surfaces or the solid");
    }
    Bnd_Box box;
    BRepBndLib::Add(shape, box);
    if (!box.IsVoid()) {
      // Checked before meshing: a pole at 1E300 would mesh for hours.
      double x0, y0, z0, x1, y1, z1;
      box.Get(x0, y0, z0, x1, y1, z1);
      const double reach = std::max(
          {std::abs(x0), std::abs(y0), std::abs(z0), std::abs(x1), std::abs(y1), std::abs(z1)});
      if (!(reach <= kMaxModelReachMm)) {
        std::ostringstream text;
        text << "the model reaches " << reach << " mm from the origin; parts within "
             << kMaxModelReachMm << " mm (100 m) of it are read (a stray point or a wrong unit?)";
        throw ModelError(Code::E4107, source, text.str());
      }
    }
    double deflection = options.deflection;
    if (deflection <= 0) {
      const double diagonal = box.IsVoid() ? 100 : std::sqrt(box.SquareExtent());
      // Over 4 m of diagonal the chord grows with the model, so the number
      // of triangles (the meshing effort) stays bounded.
      deflection = std::max(std::clamp(diagonal / 1000, 0.002, 0.2), diagonal / 20000);
    }
    BRepMesh_IncrementalMesh mesher(shape, deflection, false, 0.2, false);
    TopTools_IndexedMapOfShape solids;
    TopExp::MapShapes(shape, TopAbs_SOLID, solids);
    const bool orient_up = options.orient_open_faces_up && solids.Extent() == 0;
    add_edges(*impl, edge_map);
    for (int i = 1; i <= face_map.Extent(); ++i) {
      add_face(*impl, TopoDS::Face(face_map(i)), edge_map, orient_up);
    }
    if (impl->faces.empty()) {
      throw ModelError(Code::E4105, source, "no face of the model has a surface");
    }
    std::vector<Eigen::AlignedBox3d> boxes;
    for (const FaceData& f : impl->faces) {
      boxes.push_back(f.box);
      impl->bounds.extend(f.box);
      impl->max_slack = std::max(impl->max_slack, f.slack);
      impl->info.triangles += static_cast<int>(f.triangles.size());
    }
    impl->face_tree = BoxTree(boxes);
    impl->info.faces = static_cast<int>(impl->faces.size());
    impl->info.deflection = deflection;
  } catch (const Standard_Failure& failure) {
    throw ModelError(
        Code::E4106, source,
        std::string("OpenCASCADE failed while indexing the model: ") + failure.GetMessageString());
  }
  return BrepModel(std::move(impl));
}

}  // namespace vcpost::occt
