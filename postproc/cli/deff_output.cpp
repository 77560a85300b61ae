#include "postproc/cli/deff_output.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "postproc/deff/setup_input.h"

namespace vcpost::cli::deff_printing {

using namespace vcpost::deff;
using vcpost::deff::to_string;  // beside the local overloads below
namespace {

using geometry::CuttingPoint;
using geometry::CuttingPoints;

// Fixed decimals without a "-0.0000" for values that round to zero.
std::string fixed(double value, int decimals) {
  const double unit = std::pow(10.0, -decimals) / 2;
  if (std::abs(value) < unit) value = 0;
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

std::string fixed(const std::optional<double>& value, int decimals) {
  return value ? fixed(*value, decimals) : std::string();
}

std::string shortest(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  return buffer;
}

std::optional<double> half(const std::optional<double>& value) {
  return value ? std::optional<double>(*value / 2) : std::nullopt;
}

// The cutting points in output order, with their CSV/JSON key and the
// paper's name.
struct NamedPoint {
  const char* key;
  const char* label;
  const CuttingPoint CuttingPoints::*member;
};
constexpr std::array<NamedPoint, 7> kPoints = {{
    {"cut", "cutting point", &CuttingPoints::cut},
    {"p1", "point 1", &CuttingPoints::p1},
    {"p2", "point 2", &CuttingPoints::p2},
    {"p1a", "point 1'", &CuttingPoints::p1a},
    {"p1b", "point 1''", &CuttingPoints::p1b},
    {"p2a", "point 2'", &CuttingPoints::p2a},
    {"p2b", "point 2''", &CuttingPoints::p2b},
}};

std::optional<double> point_diameter(const Evaluation& evaluation, const NamedPoint& point) {
  const auto& points = evaluation.engagement.points;
  if (!points) return std::nullopt;
  return ((*points).*(point.member)).diameter;
}

const char* cut_point_key(geometry::Side side) {
  // The groove edge away from the previous pass (MODELS.md section 2).
  return side == geometry::Side::left ? "p1" : "p2";
}

double tilt_deg(const Eigen::Vector3d& normal) {
  return radians_to_degrees(std::acos(std::clamp(normal.z(), -1.0, 1.0)));
}

double azimuth_deg(const Eigen::Vector3d& normal) {
  if (normal.head<2>().norm() < 1e-12) return 0;
  return radians_to_degrees(std::atan2(normal.y(), normal.x()));
}

std::string_view to_string(geometry::MillingMode mode) {
  return mode == geometry::MillingMode::down ? "down" : "up";
}

std::string_view to_string(geometry::SpindleDirection direction) {
  return direction == geometry::SpindleDirection::clockwise ? "cw" : "ccw";
}

// Left-aligned first column, right-aligned numbers, two blanks between.
void write_aligned(std::ostream& out, const std::vector<std::vector<std::string>>& rows) {
  std::vector<std::size_t> widths;
  for (const auto& row : rows) {
    widths.resize(std::max(widths.size(), row.size()));
    for (std::size_t i = 0; i < row.size(); ++i) widths[i] = std::max(widths[i], row[i].size());
  }
  for (const auto& row : rows) {
    std::string line = "  ";
    for (std::size_t i = 0; i < row.size(); ++i) {
      const std::string pad(widths[i] - row[i].size(), ' ');
      line += i == 0 ? row[i] + pad : "  " + pad + row[i];
    }
    line.erase(line.find_last_not_of(' ') + 1);
    out << line << '\n';
  }
}

nlohmann::ordered_json optional_json(const std::optional<double>& value) {
  return value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

void write_table(std::ostream& out, const Description& description, const Evaluation& evaluation,
                 const std::optional<Speed>& speed, bool radius) {
  const auto& setup = description.setup;
  const auto& e = evaluation.engagement;
  out << "tool " << geometry::to_string(description.tool) << ", ap " << shortest(setup.ap)
      << " mm, ae " << shortest(setup.ae) << " mm, previous pass on the " << to_string(setup.side)
      << '\n';
  out << "normal N (" << fixed(setup.normal.x(), 4) << ", " << fixed(setup.normal.y(), 4) << ", "
      << fixed(setup.normal.z(), 4) << "): tilt " << fixed(tilt_deg(setup.normal), 2)
      << " deg, azimuth " << fixed(azimuth_deg(setup.normal), 2) << " deg\n";
  out << "feed F   (" << fixed(e.feed_dir.x(), 4) << ", " << fixed(e.feed_dir.y(), 4) << ", "
      << fixed(e.feed_dir.z(), 4) << "): unit, in the tangent plane";
  if (description.feed_angle_deg)
    out << ", feed angle " << shortest(*description.feed_angle_deg) << " deg";
  out << "\n\n";

  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> head = {"", "x [mm]", "y [mm]", "z [mm]", "2r [mm]"};
  if (radius) head.emplace_back("r [mm]");
  if (speed && speed->rpm) head.emplace_back("vc [m/min]");
  rows.push_back(head);
  const auto add_row = [&](std::string label, const Eigen::Vector3d* position,
                           const std::optional<double>& diameter) {
    std::vector<std::string> row = {std::move(label)};
    for (int i = 0; i < 3; ++i) row.push_back(position ? fixed((*position)[i], 4) : "");
    row.push_back(diameter ? fixed(*diameter, 4) : "-");
    if (radius) row.push_back(diameter ? fixed(*diameter / 2, 4) : "-");
    if (speed && speed->rpm) row.push_back(diameter ? fixed(*speed->vc_at(diameter), 2) : "-");
    rows.push_back(std::move(row));
  };
  add_row("D_max", nullptr, e.d_max);
  add_row("D_min", nullptr, e.d_min);
  add_row("D_mean", nullptr, evaluation.d_mean);
  for (std::size_t i = 1; i < kPoints.size(); ++i) {
    if (!e.points) {
      add_row(kPoints[i].label, nullptr, std::nullopt);
      continue;
    }
    const CuttingPoint& point = (*e.points).*(kPoints[i].member);
    add_row(kPoints[i].label, &point.position, point.diameter);
  }
  const bool left = setup.side == geometry::Side::left;
  const std::string cut_label = std::string("cutting point (") + (left ? "1" : "2") + ")";
  if (e.points) {
    add_row(cut_label, &e.points->cut.position, e.points->cut.diameter);
  } else {
    add_row(cut_label, nullptr, std::nullopt);
  }
  write_aligned(out, rows);
  const char* origin = description.tool.kind == geometry::ToolKind::ball ? "the ball centre"
                       : description.tool.kind == geometry::ToolKind::flat
                           ? "the end face's centre"
                           : "the centre of the corner circles' plane";
  out << "  (tool frame: origin at " << origin
      << ", z up the tool axis. '-': no such point.\n"
         "   Points 1..2'' are the paper's rim points: those behind the tool or in the\n"
         "   previous pass do not cut, so their 2r may exceed D_max.)\n\n";

  const auto flags = geometry::flag_names(e.flags);
  std::string flag_text;
  for (const auto& name : flags) flag_text += (flag_text.empty() ? "" : ", ") + name;
  const auto mode = geometry::milling_mode(setup.side, description.spindle);
  std::vector<std::vector<std::string>> facts = {
      {"engaged", e.d_max ? "yes" : "no"},
      {"flags", flags.empty() ? "none" : flag_text},
      {"milling",
       std::string(to_string(mode)) +
           (mode == geometry::MillingMode::down ? " (climb)" : " (conventional)") + ", spindle " +
           std::string(to_string(description.spindle)) +
           (description.spindle == geometry::SpindleDirection::clockwise ? " (M3)" : " (M4)")},
  };
  if (speed) {
    std::string text = "policy " + std::string(to_string(speed->policy)) + ", D_ref ";
    text += speed->d_ref ? fixed(*speed->d_ref, 4) + " mm" : std::string("none (nothing engaged)");
    if (speed->vc_nominal) {
      text += ", vc " + shortest(*speed->vc_nominal) + " m/min -> n = ";
      text += speed->rpm     ? fixed(*speed->rpm, 0) + " rpm"
              : speed->d_ref ? std::string("unbounded (D_ref is 0)")
                             : std::string("none");
    } else {
      text += ", n = " + fixed(*speed->rpm, 0) + " rpm -> vc at D_ref = ";
      text += speed->d_ref ? fixed(*speed->vc_at(speed->d_ref), 2) + " m/min" : std::string("-");
    }
    facts.push_back({"spindle", text});
  }
  for (const auto& fact : facts) {
    out << "  " << fact[0] << ':' << std::string(9 - fact[0].size(), ' ') << fact[1] << '\n';
  }
}

nlohmann::ordered_json to_json(const Description& description, const Evaluation& evaluation,
                               const std::optional<Speed>& speed) {
  const auto& setup = description.setup;
  const auto& e = evaluation.engagement;
  nlohmann::ordered_json json;
  json["tool"] = geometry::to_string(description.tool);
  json["diameter"] = description.tool.diameter;
  json["ap"] = setup.ap;
  json["ae"] = setup.ae;
  json["side"] = to_string(setup.side);
  json["normal"] = vector_json(setup.normal);
  json["tilt_deg"] = tilt_deg(setup.normal);
  json["azimuth_deg"] = azimuth_deg(setup.normal);
  json["feed"] = vector_json(e.feed_dir);
  json["feed_angle_deg"] = optional_json(description.feed_angle_deg);
  json["engaged"] = e.d_max.has_value();
  json["d_max"] = optional_json(e.d_max);
  json["d_min"] = optional_json(e.d_min);
  json["d_mean"] = optional_json(evaluation.d_mean);
  json["r_max"] = optional_json(half(e.d_max));
  json["r_min"] = optional_json(half(e.d_min));
  json["r_mean"] = optional_json(half(evaluation.d_mean));
  json["cut_point"] = cut_point_key(setup.side);
  if (e.points) {
    nlohmann::ordered_json points;
    for (const auto& named : kPoints) {
      const CuttingPoint& point = (*e.points).*(named.member);
      points[named.key] = {{"position", vector_json(point.position)},
                           {"d", point.diameter},
                           {"r", point.diameter / 2},
                           {"vc", speed ? optional_json(speed->vc_at(point.diameter))
                                        : nlohmann::ordered_json(nullptr)}};
    }
    json["points"] = points;
  } else {
    json["points"] = nullptr;
  }
  json["flags"] = geometry::flag_names(e.flags);
  json["spindle"] = to_string(description.spindle);
  json["milling"] = to_string(geometry::milling_mode(setup.side, description.spindle));
  if (speed) {
    json["speed"] = {{"policy", to_string(speed->policy)},
                     {"d_ref", optional_json(speed->d_ref)},
                     {"vc_nominal", optional_json(speed->vc_nominal)},
                     {"rpm", optional_json(speed->rpm)},
                     {"vc_max", optional_json(speed->vc_at(e.d_max))},
                     {"vc_min", optional_json(speed->vc_at(e.d_min))},
                     {"vc_mean", optional_json(speed->vc_at(evaluation.d_mean))}};
  } else {
    json["speed"] = nullptr;
  }
  return json;
}

std::string csv_header(bool radius) {
  std::string header;
  for (const char* prefix : {"d_", "r_"}) {
    if (prefix[0] == 'r' && !radius) break;
    for (const auto& point : kPoints) header += std::string(prefix) + point.key + ",";
    header += std::string(prefix) + "max," + prefix + "min," + prefix + "mean";
    if (prefix[0] == 'd') header += ",engaged";
    if (radius && prefix[0] == 'd') header += ",";
  }
  return header;
}

std::string csv_cells(const Evaluation& evaluation, bool radius) {
  const auto& e = evaluation.engagement;
  std::string cells;
  for (const double scale : {1.0, 0.5}) {
    if (scale == 0.5 && !radius) break;
    const auto scaled = [scale](const std::optional<double>& value) {
      return value ? std::optional<double>(*value * scale) : std::nullopt;
    };
    for (const auto& point : kPoints)
      cells += fixed(scaled(point_diameter(evaluation, point)), 4) + ",";
    cells += fixed(scaled(e.d_max), 4) + "," + fixed(scaled(e.d_min), 4) + "," +
             fixed(scaled(evaluation.d_mean), 4);
    if (scale == 1.0) cells += e.d_max ? ",1" : ",0";
    if (radius && scale == 1.0) cells += ",";
  }
  return cells;
}

}  // namespace vcpost::cli::deff_printing
