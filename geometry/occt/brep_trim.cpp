// A face's trim in (u,v): its boundary curves as a polygon, a grid of
// cells inside, outside or on it, and the classification of a point.
#include <BRepClass_FaceClassifier.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Line.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/occt/brep_faces.h"

namespace vcpost::occt {

using Eigen::Vector2d;

namespace {

// Even-odd crossing test of a point against the trim polygon.
bool inside_polygon(const std::vector<std::array<Vector2d, 2>>& segments, const Vector2d& q) {
  bool inside = false;
  for (const auto& [a, b] : segments) {
    if ((a.y() > q.y()) != (b.y() > q.y())) {
      const double x = a.x() + (q.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (x > q.x()) inside = !inside;
    }
  }
  return inside;
}

}  // namespace

int add_trims(FaceData& f, const TopoDS_Face& face, const TopTools_IndexedMapOfShape& edge_map) {
  int wires = 0;
  for (TopExp_Explorer w(face, TopAbs_WIRE); w.More(); w.Next()) ++wires;
  for (TopExp_Explorer x(face, TopAbs_EDGE); x.More(); x.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(x.Current());
    double a = 0, b = 0;
    Handle(Geom2d_Curve) pcurve = BRep_Tool::CurveOnSurface(edge, face, a, b);
    if (pcurve.IsNull()) continue;
    // A straight pcurve is one segment; others start as 16 and are halved
    // where the curve's midpoint is off the chord by more than 1e-7 of the
    // face's (u,v) span: a tight polygon leaves only a thin band around the
    // trim for the (slow) exact classifier.
    Handle(Geom2d_Curve) basis = pcurve;
    while (auto trimmed = Handle(Geom2d_TrimmedCurve)::DownCast(basis))
      basis = trimmed->BasisCurve();
    const auto at = [&](double t) {
      const gp_Pnt2d q = pcurve->Value(t);
      return Vector2d(q.X(), q.Y());
    };
    if (basis->IsKind(STANDARD_TYPE(Geom2d_Line))) {
      f.loops.push_back({at(a), at(b)});
    } else {
      const double tolerance = 1e-7 * std::max(f.u1 - f.u0, f.v1 - f.v0);
      constexpr int kStart = 16, kMaxDepth = 10;
      struct Piece {
        double t0, t1;
        Vector2d p0, p1;
        int depth;
      };
      std::vector<Piece> pending;
      for (int i = kStart - 1; i >= 0; --i) {
        const double t0 = a + (b - a) * i / kStart, t1 = a + (b - a) * (i + 1) / kStart;
        pending.push_back({t0, t1, at(t0), at(t1), 0});
      }
      while (!pending.empty()) {
        const Piece piece = pending.back();
        pending.pop_back();
        const double tm = (piece.t0 + piece.t1) / 2;
        const Vector2d pm = at(tm);
        const double error = (pm - (piece.p0 + piece.p1) / 2).norm();
        if (error > tolerance && piece.depth < kMaxDepth) {
          pending.push_back({tm, piece.t1, pm, piece.p1, piece.depth + 1});
          pending.push_back({piece.t0, tm, piece.p0, pm, piece.depth + 1});
        } else {
          f.loops.push_back({piece.p0, piece.p1});
          f.polygon_error = std::max(f.polygon_error, error);
        }
      }
    }
    if (BRep_Tool::Degenerated(edge) || BRep_Tool::IsClosed(edge, face)) continue;
    const int index = edge_map.FindIndex(edge) - 1;
    if (index >= 0) f.edges.push_back({index, pcurve});
  }
  return wires;
}

void classify_trim(FaceData& f, int wires) {
  const double span_u = f.u1 - f.u0, span_v = f.v1 - f.v0;
  const double eps = 1e-9 * std::max(span_u, span_v);
  const auto on_box = [&](const Vector2d& q) {
    return std::abs(q.x() - f.u0) < eps || std::abs(q.x() - f.u1) < eps ||
           std::abs(q.y() - f.v0) < eps || std::abs(q.y() - f.v1) < eps;
  };
  f.natural = wires == 1 && std::all_of(f.loops.begin(), f.loops.end(), [&](const auto& s) {
                return on_box(s[0]) && on_box(s[1]);
              });
  if (!f.natural) {
    constexpr int g = FaceData::kGrid;
    std::vector<bool> touched(g * g, false);
    const auto cell_of = [&](double x, double lo, double span) {
      return std::clamp(static_cast<int>((x - lo) / span * g), 0, g - 1);
    };
    for (const auto& [a, b] : f.loops) {
      // Cells within one cell of a segment's box are boundary cells.
      const int x0 = cell_of(std::min(a.x(), b.x()), f.u0, span_u) - 1;
      const int x1 = cell_of(std::max(a.x(), b.x()), f.u0, span_u) + 1;
      const int y0 = cell_of(std::min(a.y(), b.y()), f.v0, span_v) - 1;
      const int y1 = cell_of(std::max(a.y(), b.y()), f.v0, span_v) + 1;
      for (int x = std::max(x0, 0); x <= std::min(x1, g - 1); ++x) {
        for (int y = std::max(y0, 0); y <= std::min(y1, g - 1); ++y) touched[x * g + y] = true;
      }
    }
    // Row and cell lists (CSR), each segment listed one row or cell beyond
    // its box so rounding at the grid lines loses none.
    std::vector<std::vector<std::uint32_t>> rows(g), cells(g * g);
    for (std::size_t i = 0; i < f.loops.size(); ++i) {
      const auto& [a, b] = f.loops[i];
      const int x0 = cell_of(std::min(a.x(), b.x()), f.u0, span_u) - 1;
      const int x1 = cell_of(std::max(a.x(), b.x()), f.u0, span_u) + 1;
      const int y0 = cell_of(std::min(a.y(), b.y()), f.v0, span_v) - 1;
      const int y1 = cell_of(std::max(a.y(), b.y()), f.v0, span_v) + 1;
      for (int y = std::max(y0, 0); y <= std::min(y1, g - 1); ++y) {
        rows[static_cast<std::size_t>(y)].push_back(static_cast<std::uint32_t>(i));
        for (int x = std::max(x0, 0); x <= std::min(x1, g - 1); ++x) {
          cells[grid_index(x, g, y)].push_back(static_cast<std::uint32_t>(i));
        }
      }
    }
    const auto flatten = [](const std::vector<std::vector<std::uint32_t>>& lists,
                            std::vector<std::uint32_t>& start, std::vector<std::uint32_t>& flat) {
      start.assign(1, 0);
      for (const auto& list : lists) {
        flat.insert(flat.end(), list.begin(), list.end());
        start.push_back(static_cast<std::uint32_t>(flat.size()));
      }
    };
    flatten(rows, f.row_start, f.row_segments);
    flatten(cells, f.cell_start, f.cell_segments);
    const double band = 2 * f.polygon_error + 1e-9 * std::max(span_u, span_v);
    f.local_lists = band < std::min(span_u, span_v) / g;
    f.cells.resize(g * g);
    for (int x = 0; x < g; ++x) {
      for (int y = 0; y < g; ++y) {
        const Vector2d centre(f.u0 + (x + 0.5) * span_u / g, f.v0 + (y + 0.5) * span_v / g);
        f.cells[x * g + y] = touched[x * g + y]                ? Trim::boundary
                             : inside_polygon(f.loops, centre) ? Trim::inside
                                                               : Trim::outside;
      }
    }
  }
}

Trim classify(const FaceData& f, const Vector2d& uv) {
  if (f.natural) return Trim::inside;
  const int gx = std::clamp(static_cast<int>((uv.x() - f.u0) / (f.u1 - f.u0) * FaceData::kGrid), 0,
                            FaceData::kGrid - 1);
  const int gy = std::clamp(static_cast<int>((uv.y() - f.v0) / (f.v1 - f.v0) * FaceData::kGrid), 0,
                            FaceData::kGrid - 1);
  const Trim cell = f.cells[grid_index(gx, FaceData::kGrid, gy)];
  if (cell != Trim::boundary) return cell;
  // The polygon decides unless the point is within its chord error of it.
  bool inside = false;
  double nearest = std::numeric_limits<double>::infinity();
  const auto cross = [&](const std::array<Vector2d, 2>& segment) {
    const auto& [a, b] = segment;
    if ((a.y() > uv.y()) != (b.y() > uv.y())) {
      const double x = a.x() + (uv.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (x > uv.x()) inside = !inside;
    }
  };
  const auto near = [&](const std::array<Vector2d, 2>& segment) {
    const auto& [a, b] = segment;
    const Vector2d ab = b - a;
    const double t = std::clamp((uv - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
    nearest = std::min(nearest, (a + t * ab - uv).squaredNorm());
  };
  if (f.local_lists) {
    const auto row = static_cast<std::size_t>(gy);
    for (std::uint32_t i = f.row_start[row]; i < f.row_start[row + 1]; ++i) {
      cross(f.loops[f.row_segments[i]]);
    }
    const auto at = grid_index(gx, FaceData::kGrid, gy);
    for (std::uint32_t i = f.cell_start[at]; i < f.cell_start[at + 1]; ++i) {
      near(f.loops[f.cell_segments[i]]);
    }
  } else {
    for (const auto& segment : f.loops) {
      cross(segment);
      near(segment);
    }
  }
  const double band = 2 * f.polygon_error + 1e-9 * std::max(f.u1 - f.u0, f.v1 - f.v0);
  if (nearest > band * band) return inside ? Trim::inside : Trim::outside;
  // Near the boundary the polygon is not exact: classify on the pcurves.
  const double tol = 1e-9 * std::max(f.u1 - f.u0, f.v1 - f.v0);
  BRepClass_FaceClassifier classifier(f.face, gp_Pnt2d(uv.x(), uv.y()), tol);
  const TopAbs_State state = classifier.State();
  return state == TopAbs_IN ? Trim::inside : state == TopAbs_OUT ? Trim::outside : Trim::boundary;
}

}  // namespace vcpost::occt
