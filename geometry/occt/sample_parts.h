// STEP files of the sample parts (one face each), written with
// OpenCASCADE from surfaces given as plain values, so the sample generator's
// closed forms and the STEP model are the same surface. No OCCT types here.
//
// Units: mm (the file declares millimetres), radians. Each writer makes one
// face on the exact surface (no approximation) and writes an AP214 STEP
// file through a temporary file renamed when complete. Throws
// std::runtime_error naming the path when OCCT or the file system fails.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace vcpost::occt {

// A non-rational B-spline surface: full knot vectors (with repetition),
// count_u x count_v poles in row-major order (poles[i * count_v + j]).
struct BsplineSurfaceSpec {
  int degree_u = 3, degree_v = 3;
  std::vector<double> knots_u, knots_v;
  int count_u = 0, count_v = 0;
  std::vector<Eigen::Vector3d> poles;
};

void write_bspline_face_step(const std::filesystem::path& path, const BsplineSurfaceSpec& surface,
                             const std::string& name);

// The same surface cut into nu x nv faces at equal steps of its knot range
// in u and v, sewn into one open shell (neighbours share edges and
// vertices): a multi-face STEP model whose faces together are exactly the
// uncut surface, so the uncut surface's truth holds for it. REQUIRES nu,
// nv >= 1.
void write_bspline_patches_step(const std::filesystem::path& path,
                                const BsplineSurfaceSpec& surface, int nu, int nv,
                                const std::string& name);

// The cylinder origin + h*axis + radius*(cos a*ref + sin a*(axis x ref)),
// a in [angle_min, angle_max], h in [h_min, h_max]. REQUIRES unit,
// perpendicular axis and ref.
void write_cylinder_face_step(const std::filesystem::path& path, const Eigen::Vector3d& origin,
                              const Eigen::Vector3d& axis, const Eigen::Vector3d& ref,
                              double radius, double angle_min, double angle_max, double h_min,
                              double h_max, const std::string& name);

// The sphere centre + radius*(cos lat*(cos lon*ref + sin lon*(pole x ref)) +
// sin lat*pole), lon in [0, 2 pi], lat in [lat_min, lat_max] (pi/2 = the pole).
void write_sphere_face_step(const std::filesystem::path& path, const Eigen::Vector3d& centre,
                            const Eigen::Vector3d& pole, const Eigen::Vector3d& ref, double radius,
                            double lat_min, double lat_max, const std::string& name);

}  // namespace vcpost::occt
