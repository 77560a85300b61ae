// The finished-surface model as the rest of vcpost sees it: one closest-point
// query, plus what docs/models.md §1 derives from it for a ball-end mill.
//
// Units: mm everywhere. Implementations: geometry/analytic_surfaces.h (exact
// closed forms, for tests and samples), geometry/occt/ (STEP through
// OpenCASCADE), the STL mesh model. No OpenCASCADE in this header.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>

namespace vcpost::geometry {

// The farthest a point of the part, model or toolpath, may lie from the
// origin, mm: the part must fit a machine. Beyond it the input is refused
// before any effort that grows with its size (meshing, flattening curves).
inline constexpr double kMaxReachMm = 1e5;

// Where on its face the closest point lies: inside the face, on one of its
// boundary edges, or on a vertex (an end of an edge).
enum class ContactType { face, edge, vertex };

std::string_view to_string(ContactType type);

// Principal curvatures at a surface point, signed so that a surface bending
// away from its normal N (convex seen from the tool, e.g. the outside of a
// solid sphere of radius r: +1/r) is positive and a concave one negative.
// k1 >= k2; d1, d2 are the unit principal directions (tangent, d1 x d2 = N).
// Units: 1/mm.
struct PrincipalCurvatures {
  double k1 = 0, k2 = 0;
  Eigen::Vector3d d1 = Eigen::Vector3d::UnitX(), d2 = Eigen::Vector3d::UnitY();
};

// The closest point of the model to a query point.
struct ModelContact {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // CC, mm
  Eigen::Vector3d normal =
      Eigen::Vector3d::UnitZ();  // unit surface normal at CC, out of the material
  double distance = 0;           // |query - CC| >= 0, mm
  // Of the owning face at CC; empty for meshes and when the hint asks for none.
  std::optional<PrincipalCurvatures> curvature;
  int face = -1;                                 // index of the owning face, [0, face_count())
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();  // parameters on that face (model-specific)
  ContactType type = ContactType::face;
};

// Per-thread warm start: the face and (u,v) of the previous query. One hint
// per thread (or per coherent chunk of the path); never shared between
// threads. A default hint makes the next query cold (through the index).
struct ContactHint {
  int face = -1;
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  // The previous query's point: a query farther from it than its search
  // distance is answered cold (Newton's method started that far away may
  // stop in another local minimum, as at a new tool's first point).
  Eigen::Vector3d query = Eigen::Vector3d::Zero();
  // Whether answers carry curvatures (only reports read them; leaving them
  // out saves the second fundamental form on every query).
  bool curvature = true;
  // Bull-nose and flat end mills (tool_contact.h): the previous contact's
  // core disc point, relative to the disc's centre (xy, mm); when it and
  // the one before lay on the rim, the angle the contact turned between
  // them (rad), and how much that turn changed from the turn before (0:
  // unknown), which give the next one's first guess; and the rim solve's
  // last slope (0: unknown).
  Eigen::Vector2d rim = Eigen::Vector2d::Zero();
  double rim_turn = 0;
  double rim_turn_change = 0;
  double rim_slope = 0;
  // Counters, for reports and benchmarks only.
  std::uint64_t warm_queries = 0;  // answered from the hint
  std::uint64_t cold_queries = 0;  // went through the spatial index
};

// The seam between vcpost and a geometry kernel.
// Thread safety: a model is immutable after construction; closest_point is
// const and may be called from many threads at once, each with its own hint.
class SurfaceModel {
 public:
  virtual ~SurfaceModel() = default;

  // The point of the model closest to `point` (ties: any of them), when it
  // is within `max_distance` mm; empty otherwise (or when the model is
  // empty). `hint` may be null (a cold query); when given it is read as a
  // warm start and updated to this answer.
  virtual std::optional<ModelContact> closest_point(const Eigen::Vector3d& point,
                                                    double max_distance,
                                                    ContactHint* hint) const = 0;

  // Axis-aligned box holding the whole model, mm.
  virtual Eigen::AlignedBox3d bounds() const = 0;

  virtual int face_count() const = 0;

  // Whether the surface is made of flat facets (a mesh): its normals are
  // constant over each facet, not smooth (tool_contact.h solves smooth
  // surfaces' rim contacts by secant steps, facets' by gradient steps).
  virtual bool faceted() const { return false; }

 protected:
  SurfaceModel() = default;
  SurfaceModel(const SurfaceModel&) = default;
  SurfaceModel& operator=(const SurfaceModel&) = default;
};

// Which point of a ball-end mill the toolpath gives (docs/models.md §1).
enum class ClPoint { tip, center };

// Ball centre C from a CL point: C = CL + R*axis for the tip, CL itself for
// the centre. `axis` is the unit tool axis (+z on a 3-axis machine).
Eigen::Vector3d ball_center(const Eigen::Vector3d& cl_point, double radius, ClPoint kind,
                            const Eigen::Vector3d& axis = Eigen::Vector3d::UnitZ());

// How the ball sits on the model.
enum class BallStatus {
  touching,  // |distance error| <= tolerance
  lifted,    // the ball is clear of the surface by more than the tolerance
  gouging,   // the ball reaches into the material by more than the tolerance
  missed,    // no surface within the search distance: the path does not touch the model
};

std::string_view to_string(BallStatus status);

// The docs/models.md §1 quantities at one toolpath point.
struct BallContact {
  BallStatus status = BallStatus::missed;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // C, mm
  // N = (C - CC)/|C - CC|, the normal the tool sees; when C lies behind the
  // surface (inside the material) or on it, the surface normal at CC instead.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  // Signed distance of C from the surface minus R, mm: > 0 lifted, < 0 gouge.
  // With C behind the surface the signed distance is -|C - CC|.
  double distance_error = 0;
  std::optional<ModelContact> contact;  // empty when missed
};

// Classifies a contact already found for centre C (pure; no model access).
// REQUIRES: radius > 0, tolerance >= 0.
BallContact classify_ball_contact(const Eigen::Vector3d& center, double radius, double tolerance,
                                  const std::optional<ModelContact>& contact);

// Queries `model` for centre C and classifies: the surface is searched up to
// radius + search_margin from C; nothing there gives BallStatus::missed.
// REQUIRES: radius > 0, tolerance >= 0, search_margin >= 0.
BallContact ball_contact(const SurfaceModel& model, const Eigen::Vector3d& center, double radius,
                         double tolerance, double search_margin, ContactHint* hint);

}  // namespace vcpost::geometry
