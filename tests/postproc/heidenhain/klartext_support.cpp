#include "tests/postproc/heidenhain/klartext_support.h"

namespace vcpost::heidenhain::testing {

using program::Event;

std::vector<Event> run(std::string_view text, Interpreter* keep) {
  Interpreter own(text);
  Interpreter& interpreter = keep ? *keep : own;
  std::vector<Event> events;
  while (interpreter.next(events)) {
  }
  return events;
}

std::vector<Event> motions(const std::vector<Event>& events) {
  std::vector<Event> out;
  for (const Event& e : events)
    if (program::is_motion(e)) out.push_back(e);
  return out;
}

Eigen::Vector3d end_of(const Event& e) {
  if (const auto* t = std::get_if<program::StraightTraverse>(&e)) return t->end;
  if (const auto* f = std::get_if<program::StraightFeed>(&e)) return f->end;
  return std::get<program::ArcFeed>(e).end;
}

std::vector<Eigen::Vector3d> program_ends(const std::vector<Event>& events) {
  std::vector<Eigen::Vector3d> out;
  program::WorkingFrame frame;
  for (const Event& e : events) {
    if (const auto* f = std::get_if<program::WorkingFrame>(&e)) frame = *f;
    if (program::is_motion(e)) out.push_back(frame.to_program(end_of(e)));
  }
  return out;
}

void expect_point(const Eigen::Vector3d& p, double x, double y, double z, double tol) {
  EXPECT_NEAR(p.x(), x, tol);
  EXPECT_NEAR(p.y(), y, tol);
  EXPECT_NEAR(p.z(), z, tol);
}

Code error_of(std::string_view text) {
  InterpreterLimits limits;
  limits.max_loop_iterations = 1000;  // an endless loop ends fast
  Interpreter interpreter(text, limits);
  try {
    run("", &interpreter);
  } catch (const KlartextError& e) {
    return e.diagnostic().code;
  }
  return Code::W3343;  // no error
}

}  // namespace vcpost::heidenhain::testing
