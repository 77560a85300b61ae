#include "geometry/occt/sample_shapes.h"

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRep_Tool.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <cmath>
#include <numbers>

namespace vcpost::occt {

TopoDS_Face wavy_bspline_face(double size, int poles, double amplitude, double wavelength) {
  constexpr int kDegree = 3;
  TColgp_Array2OfPnt points(1, poles, 1, poles);
  const double k = 2 * std::numbers::pi / wavelength;
  for (int i = 1; i <= poles; ++i) {
    for (int j = 1; j <= poles; ++j) {
      const double x = size * (i - 1) / (poles - 1), y = size * (j - 1) / (poles - 1);
      points(i, j) = gp_Pnt(x, y, amplitude * std::sin(k * x) * std::cos(k * y));
    }
  }
  // Clamped uniform knots on [0, 1]: end multiplicity degree + 1.
  const int knots = poles - kDegree + 1;
  TColStd_Array1OfReal values(1, knots);
  TColStd_Array1OfInteger mults(1, knots);
  for (int i = 1; i <= knots; ++i) {
    values(i) = static_cast<double>(i - 1) / (knots - 1);
    mults(i) = (i == 1 || i == knots) ? kDegree + 1 : 1;
  }
  Handle(Geom_BSplineSurface) surface =
      new Geom_BSplineSurface(points, values, values, mults, mults, kDegree, kDegree);
  return BRepBuilderAPI_MakeFace(surface, 1e-7).Face();
}

TopoDS_Shape wavy_patches(int nu, int nv, double size, int poles, double amplitude,
                          double wavelength) {
  const TopoDS_Face face = wavy_bspline_face(size, poles, amplitude, wavelength);
  return bspline_patches(Handle(Geom_BSplineSurface)::DownCast(BRep_Tool::Surface(face)), nu, nv);
}

}  // namespace vcpost::occt
