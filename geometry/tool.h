// Milling tools as the working-diameter engine sees them.
#pragma once

#include <string>
#include <string_view>

namespace vcpost::geometry {

enum class ToolKind { ball, bull_nose, flat };

// A tool of revolution about +z. The tool frame's origin is the centre of
// the corner circle's plane: for a ball the ball centre, for a bull-nose the
// plane of the torus' tube-centre circle (the tip lies corner_radius below
// it), for a flat end mill the end face (corner_radius 0).
// Above z = 0 every tool is a cylindrical shank of radius R = D/2.
struct Tool {
  ToolKind kind = ToolKind::ball;
  double diameter = 0;       // D, mm, > 0
  double corner_radius = 0;  // rc, mm: R for a ball, 0 for a flat mill, (0, R) for a bull-nose

  double radius() const { return diameter / 2; }
  double flat_radius() const { return radius() - corner_radius; }  // R0 = R - rc

  static Tool ball(double diameter) { return {ToolKind::ball, diameter, diameter / 2}; }
  static Tool bull_nose(double diameter, double corner_radius) {
    return {ToolKind::bull_nose, diameter, corner_radius};
  }
  static Tool flat(double diameter) { return {ToolKind::flat, diameter, 0}; }
};

// Parses "ball:D", "bull:D:rc" and "flat:D" (mm), e.g. "ball:10", "bull:12:2".
// Throws std::invalid_argument with a message naming the bad part for an
// unknown kind, a missing or non-numeric size, D <= 0, or rc outside (0, D/2].
// "bull:D:rc" with rc = D/2 is the ball "ball:D".
Tool parse_tool(std::string_view spec);

// The inverse of parse_tool, e.g. "ball:10".
std::string to_string(const Tool& tool);

std::string_view to_string(ToolKind kind);

}  // namespace vcpost::geometry
