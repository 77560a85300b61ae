#include "geometry/rigid_transform.h"

#include <Eigen/SVD>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>
#include <vector>

#include "core/text.h"

namespace vcpost::geometry {
namespace {

[[noreturn]] void fail_syntax(const std::string& message) {
  throw TransformError(Code::E4110, "--model-transform: " + message);
}

std::vector<std::string_view> split(std::string_view text) {
  std::vector<std::string_view> items;
  for (;;) {
    const std::size_t comma = text.find(',');
    items.push_back(trim(text.substr(0, comma), kBlanks));
    if (comma == std::string_view::npos) return items;
    text.remove_prefix(comma + 1);
  }
}

double number(std::string_view text, std::string_view step) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() ||
      !std::isfinite(value)) {
    fail_syntax("'" + std::string(step) + "': '" + std::string(text) + "' is not a number");
  }
  return value;
}

// cos and sin of a turn, exact at multiples of 90 degrees (so that a model
// turned by -90 keeps its planes axis-aligned to the last bit).
std::pair<double, double> cos_sin(double degrees) {
  const double quarter = degrees / 90;
  if (quarter == std::round(quarter)) {
    static constexpr std::array<std::pair<double, double>, 4> kQuarters{
        {{1, 0}, {0, 1}, {-1, 0}, {0, -1}}};
    const auto index = static_cast<long long>(std::fmod(quarter, 4));
    return kQuarters[static_cast<std::size_t>((index + 4) % 4)];
  }
  const double radians = degrees * std::numbers::pi / 180;
  return {std::cos(radians), std::sin(radians)};
}

}  // namespace

RigidTransform turn_about(int axis, double degrees) {
  const auto [c, s] = cos_sin(degrees);
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;
  RigidTransform turn;
  turn.rotation(a, a) = c;
  turn.rotation(a, b) = -s;
  turn.rotation(b, a) = s;
  turn.rotation(b, b) = c;
  return turn;
}

RigidTransform rigid_from_matrix(const Eigen::Matrix4d& matrix) {
  const Eigen::Matrix3d r = matrix.topLeftCorner<3, 3>();
  const double skew = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  const double bottom = (matrix.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff();
  std::ostringstream why;
  why << std::setprecision(3);
  if (!(skew <= kRigidTolerance)) {
    why << "its 3x3 part is not orthonormal (R^T R differs from I by up to " << skew
        << "): it scales or shears the model";
  } else if (!(r.determinant() > 0)) {
    why << "it mirrors the model (determinant " << r.determinant()
        << "): a mirrored part is another part";
  } else if (!(bottom <= kRigidTolerance)) {
    why << "its last row is not 0,0,0,1 (a projective matrix)";
  }
  const Eigen::Vector3d shift = matrix.topRightCorner<3, 1>();
  if (why.tellp() == 0 && !(shift.cwiseAbs().maxCoeff() <= kMaxReachMm))
    why << "its shift reaches beyond 100000 mm";
  if (why.tellp() != 0) {
    throw TransformError(Code::E4111,
                         "--model-transform: the matrix is not a rigid transform: " + why.str());
  }
  // The nearest rotation (R = U V^T), so that typed decimals leave no scale.
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return {svd.matrixU() * svd.matrixV().transpose(), shift};
}

RigidTransform parse_rigid_transform(std::string_view text) {
  const std::vector<std::string_view> items = split(text);
  RigidTransform total;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string_view step = items[i];
    const std::size_t equals = step.find('=');
    if (step.empty()) fail_syntax("an empty step (two commas, or a comma at an end)");
    if (equals == std::string_view::npos) {
      fail_syntax("'" + std::string(step) +
                  "': expected rx=DEG, ry=DEG, rz=DEG, x=MM, y=MM, z=MM or matrix=16 numbers");
    }
    const std::string key = to_lower(trim(step.substr(0, equals), kBlanks));
    const std::string_view value = trim(step.substr(equals + 1), kBlanks);
    RigidTransform next;
    if (key == "matrix") {
      if (items.size() - i < 16) {
        fail_syntax("matrix= takes 16 numbers (4 rows of 4), " + std::to_string(items.size() - i) +
                    " given");
      }
      Eigen::Matrix4d m;
      for (int k = 0; k < 16; ++k)
        m(k / 4, k % 4) = number(k == 0 ? value : items[i + static_cast<std::size_t>(k)], step);
      i += 15;
      next = rigid_from_matrix(m);
    } else if (key.size() == 2 && key[0] == 'r' && key[1] >= 'x' && key[1] <= 'z') {
      next = turn_about(key[1] - 'x', number(value, step));
    } else if (key.size() == 1 && key[0] >= 'x' && key[0] <= 'z') {
      const double mm = number(value, step);
      if (!(std::abs(mm) <= kMaxReachMm))
        fail_syntax("'" + std::string(step) + "': a shift beyond 100000 mm");
      next.shift[key[0] - 'x'] = mm;
    } else {
      fail_syntax("'" + std::string(step) +
                  "': unknown step; expected rx, ry, rz (degrees), x, y, z (mm) or matrix");
    }
    total = total.then(next);
  }
  if (!(total.shift.cwiseAbs().maxCoeff() <= kMaxReachMm))
    fail_syntax("the shifts add up to beyond 100000 mm");
  return total;
}

std::string to_string(const RigidTransform& transform) {
  if (transform.is_identity()) return "identity";
  std::ostringstream out;
  out << std::setprecision(10) << "matrix=";
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) out << transform.rotation(row, col) + 0.0 << ',';
    out << transform.shift[row] + 0.0 << ',';
  }
  out << "0,0,0,1";
  return out.str();
}

TransformedModel::TransformedModel(std::shared_ptr<const SurfaceModel> base,
                                   const RigidTransform& placement)
    : base_(std::move(base)), placement_(placement) {}

std::optional<ModelContact> TransformedModel::closest_point(const Eigen::Vector3d& point,
                                                            double max_distance,
                                                            ContactHint* hint) const {
  // The hint's query point is kept in this model's (the program's) frame, as
  // every other user of the hint sees it; the base compares it in its own.
  if (hint) hint->query = placement_.unapply(hint->query);
  std::optional<ModelContact> contact =
      base_->closest_point(placement_.unapply(point), max_distance, hint);
  if (hint) hint->query = placement_.apply(hint->query);
  if (!contact) return contact;
  const Eigen::Matrix3d& r = placement_.rotation;
  contact->point = placement_.apply(contact->point);
  contact->normal = r * contact->normal;
  if (contact->curvature) {
    contact->curvature->d1 = r * contact->curvature->d1;
    contact->curvature->d2 = r * contact->curvature->d2;
  }
  return contact;
}

Eigen::AlignedBox3d TransformedModel::bounds() const {
  const Eigen::AlignedBox3d box = base_->bounds();
  if (box.isEmpty()) return box;
  Eigen::AlignedBox3d placed;
  for (int corner = 0; corner < 8; ++corner)
    placed.extend(
        placement_.apply(box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner))));
  return placed;
}

}  // namespace vcpost::geometry
