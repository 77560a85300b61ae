// Helpers of the Klartext reader's tests: run a program text to its end,
// pick its motions, their end points (in the event's frame or the
// program's), and the code of the error a program stops with.
#pragma once

#include <gtest/gtest.h>

#include <string_view>
#include <vector>

#include "postproc/heidenhain/interpreter.h"

namespace vcpost::heidenhain::testing {

// The events of `text` run to its end (by `keep` when given, so that its
// state can be read afterwards; `text` is then ignored).
std::vector<program::Event> run(std::string_view text, Interpreter* keep = nullptr);

// The motions only, in order.
std::vector<program::Event> motions(const std::vector<program::Event>& events);

// A motion's end, in its event's frame.
Eigen::Vector3d end_of(const program::Event& e);

// Each motion's end where it is in the program (untilted) frame: the
// WorkingFrame in effect turns the event's point out (events.h).
std::vector<Eigen::Vector3d> program_ends(const std::vector<program::Event>& events);

void expect_point(const Eigen::Vector3d& p, double x, double y, double z, double tol = 1e-9);

// The code of the error `text` stops with; Code::W3343 when none
// (loops are bounded at 1000 jumps).
Code error_of(std::string_view text);

}  // namespace vcpost::heidenhain::testing
