#include "geometry/occt/sample_parts.h"

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Ax3.hxx>
#include <stdexcept>

#include "geometry/occt/quiet_messenger.h"
#include "geometry/occt/sample_shapes.h"

// The sample parts are written by vcpost-samplegen and the tests, never by
// vcpost: their failures stay std::runtime_error, which samplegen's main
// prints (they are no input of the user's to fix, so carry no code).
namespace vcpost::occt {
namespace {

gp_Pnt pnt(const Eigen::Vector3d& p) { return gp_Pnt(p.x(), p.y(), p.z()); }
gp_Dir dir(const Eigen::Vector3d& d) { return gp_Dir(d.x(), d.y(), d.z()); }

// Distinct knots and their multiplicities, as OCCT takes them.
void split_knots(const std::vector<double>& full, TColStd_Array1OfReal& knots,
                 TColStd_Array1OfInteger& mults) {
  std::vector<double> k;
  std::vector<int> m;
  for (double t : full) {
    if (!k.empty() && t == k.back()) {
      ++m.back();
    } else {
      k.push_back(t);
      m.push_back(1);
    }
  }
  knots.Resize(1, static_cast<int>(k.size()), false);
  mults.Resize(1, static_cast<int>(m.size()), false);
  for (std::size_t i = 0; i < k.size(); ++i) {
    knots.SetValue(static_cast<int>(i) + 1, k[i]);
    mults.SetValue(static_cast<int>(i) + 1, m[i]);
  }
}

void write_shape(const std::filesystem::path& path, const TopoDS_Shape& shape,
                 const std::string& name) {
  const std::filesystem::path temporary = path.string() + ".partial";
  const QuietMessenger quiet;  // the writer prints transfer statistics on stdout
  try {
    Interface_Static::SetCVal("write.step.unit", "MM");
    Interface_Static::SetCVal("write.step.schema", "AP214IS");
    Interface_Static::SetCVal("write.step.product.name", name.c_str());
    STEPControl_Writer writer;
    if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone) {
      throw std::runtime_error(path.string() +
                               ": OpenCASCADE could not translate the face to STEP");
    }
    if (writer.Write(temporary.string().c_str()) != IFSelect_RetDone) {
      throw std::runtime_error(path.string() + ": cannot write the STEP file");
    }
  } catch (const Standard_Failure& e) {
    std::filesystem::remove(temporary);
    throw std::runtime_error(path.string() + ": OpenCASCADE failed: " + e.GetMessageString());
  }
  std::filesystem::rename(temporary, path);
}

TopoDS_Face make_face(const Handle(Geom_Surface) & surface, double u0, double u1, double v0,
                      double v1, const std::string& what) {
  BRepBuilderAPI_MakeFace maker(surface, u0, u1, v0, v1, 1e-9);
  if (!maker.IsDone()) throw std::runtime_error("cannot make the " + what + " face");
  return maker.Face();
}

Handle(Geom_BSplineSurface)
    make_bspline(const std::filesystem::path& path, const BsplineSurfaceSpec& s) {
  if (s.count_u * s.count_v != static_cast<int>(s.poles.size())) {
    throw std::runtime_error(path.string() + ": B-spline pole count does not match its grid");
  }
  try {
    TColgp_Array2OfPnt poles(1, s.count_u, 1, s.count_v);
    for (int i = 0; i < s.count_u; ++i)
      for (int j = 0; j < s.count_v; ++j)
        poles.SetValue(i + 1, j + 1, pnt(s.poles[i * s.count_v + j]));
    TColStd_Array1OfReal ku(1, 1), kv(1, 1);
    TColStd_Array1OfInteger mu(1, 1), mv(1, 1);
    split_knots(s.knots_u, ku, mu);
    split_knots(s.knots_v, kv, mv);
    return new Geom_BSplineSurface(poles, ku, kv, mu, mv, s.degree_u, s.degree_v);
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(path.string() +
                             ": OpenCASCADE refused the B-spline: " + e.GetMessageString());
  }
}

}  // namespace

TopoDS_Shape bspline_patches(const Handle(Geom_BSplineSurface) & surface, int nu, int nv) {
  if (surface.IsNull() || nu < 1 || nv < 1) {
    throw std::runtime_error("bspline_patches: needs a surface and at least one patch each way");
  }
  try {
    double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
    surface->Bounds(u0, u1, v0, v1);
    // Tolerance for merging the shared boundaries: the cut edges of two
    // neighbours are the same iso-curve up to rounding.
    BRepBuilderAPI_Sewing sewing(1e-6);
    for (int i = 0; i < nu; ++i) {
      for (int j = 0; j < nv; ++j) {
        const double a = u0 + (u1 - u0) * i / nu,
                     b = i + 1 == nu ? u1 : u0 + (u1 - u0) * (i + 1) / nu;
        const double c = v0 + (v1 - v0) * j / nv,
                     d = j + 1 == nv ? v1 : v0 + (v1 - v0) * (j + 1) / nv;
        Handle(Geom_BSplineSurface) piece = Handle(Geom_BSplineSurface)::DownCast(surface->Copy());
        piece->Segment(a, b, c, d);
        BRepBuilderAPI_MakeFace maker(piece, 1e-9);
        if (!maker.IsDone()) throw std::runtime_error("bspline_patches: cannot make a patch face");
        sewing.Add(maker.Face());
      }
    }
    sewing.Perform();
    TopoDS_Shape sewn = sewing.SewedShape();
    if (sewn.IsNull()) throw std::runtime_error("bspline_patches: sewing gave no shape");
    return sewn;
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(std::string("bspline_patches: OpenCASCADE failed: ") +
                             e.GetMessageString());
  }
}

void write_shape_step(const std::filesystem::path& path, const TopoDS_Shape& shape,
                      const std::string& name) {
  write_shape(path, shape, name);
}

void write_bspline_face_step(const std::filesystem::path& path, const BsplineSurfaceSpec& s,
                             const std::string& name) {
  const Handle(Geom_BSplineSurface) surface = make_bspline(path, s);
  TopoDS_Face face;
  try {
    BRepBuilderAPI_MakeFace maker(surface, 1e-9);
    if (!maker.IsDone())
      throw std::runtime_error(path.string() + ": cannot make the B-spline face");
    face = maker.Face();
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(path.string() +
                             ": OpenCASCADE refused the B-spline: " + e.GetMessageString());
  }
  write_shape(path, face, name);
}

void write_bspline_patches_step(const std::filesystem::path& path, const BsplineSurfaceSpec& s,
                                int nu, int nv, const std::string& name) {
  const Handle(Geom_BSplineSurface) surface = make_bspline(path, s);
  TopoDS_Shape shape;
  try {
    shape = bspline_patches(surface, nu, nv);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path.string() + ": " + e.what());
  }
  write_shape(path, shape, name);
}

void write_cylinder_face_step(const std::filesystem::path& path, const Eigen::Vector3d& origin,
                              const Eigen::Vector3d& axis, const Eigen::Vector3d& ref,
                              double radius, double angle_min, double angle_max, double h_min,
                              double h_max, const std::string& name) {
  TopoDS_Face face;
  try {
    Handle(Geom_CylindricalSurface) surface =
        new Geom_CylindricalSurface(gp_Ax3(pnt(origin), dir(axis), dir(ref)), radius);
    face = make_face(surface, angle_min, angle_max, h_min, h_max, "cylinder");
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(path.string() +
                             ": OpenCASCADE refused the cylinder: " + e.GetMessageString());
  }
  write_shape(path, face, name);
}

void write_sphere_face_step(const std::filesystem::path& path, const Eigen::Vector3d& centre,
                            const Eigen::Vector3d& pole, const Eigen::Vector3d& ref, double radius,
                            double lat_min, double lat_max, const std::string& name) {
  TopoDS_Face face;
  try {
    Handle(Geom_SphericalSurface) surface =
        new Geom_SphericalSurface(gp_Ax3(pnt(centre), dir(pole), dir(ref)), radius);
    face = make_face(surface, 0, 2 * M_PI, lat_min, lat_max, "sphere");
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(path.string() +
                             ": OpenCASCADE refused the sphere: " + e.GetMessageString());
  }
  write_shape(path, face, name);
}

}  // namespace vcpost::occt
