#include "postproc/verify/verify_detail.h"

#include <algorithm>
#include <type_traits>

#include "postproc/program/transcript.h"

namespace vcpost::verify {

void ViolationSink::add(Code code, std::uint32_t line, std::uint32_t column,
                        std::uint32_t input_line, std::string message) {
  ++count_;
  ++by_code_[code];
  lines_.insert(line);
  if (kept_.size() < keep_)
    kept_.push_back(Violation{code, line, column, input_line, std::move(message)});
}

std::uint64_t ViolationSink::count_of(Code code) const {
  const auto it = by_code_.find(code);
  return it == by_code_.end() ? 0 : it->second;
}

void ViolationSink::move_into(Result& result) {
  std::stable_sort(kept_.begin(), kept_.end(), [](const Violation& a, const Violation& b) {
    return a.line != b.line ? a.line < b.line : a.column < b.column;
  });
  result.violations = std::move(kept_);
  result.violation_count = count_;
}

namespace {

using namespace program;

// Field by field, source aside (the caller compares its line).
bool same_fields(const StraightTraverse& a, const StraightTraverse& b) {
  return a.start == b.start && a.end == b.end;
}
bool same_fields(const StraightFeed& a, const StraightFeed& b) {
  return a.start == b.start && a.end == b.end;
}
bool same_fields(const ArcFeed& a, const ArcFeed& b) {
  return a.start == b.start && a.end == b.end && a.centre == b.centre && a.plane == b.plane &&
         a.rotation == b.rotation;
}
bool same_fields(const SetFeedRate& a, const SetFeedRate& b) {
  return a.rate == b.rate && a.mode == b.mode && a.path_rate == b.path_rate;
}
bool same_fields(const SetSpindleSpeed& a, const SetSpindleSpeed& b) { return a.rpm == b.rpm; }
bool same_fields(const SpindleOn& a, const SpindleOn& b) { return a.direction == b.direction; }
bool same_fields(const SpindleOff& /*a*/, const SpindleOff& /*b*/) { return true; }
bool same_fields(const SelectTool& a, const SelectTool& b) { return a.number == b.number; }
bool same_fields(const ChangeTool& a, const ChangeTool& b) { return a.number == b.number; }
bool same_fields(const ToolLengthOffset& a, const ToolLengthOffset& b) {
  return a.enabled == b.enabled && a.register_number == b.register_number;
}
bool same_fields(const CutterCompensation& a, const CutterCompensation& b) {
  return a.side == b.side;
}
bool same_fields(const SelectPlane& a, const SelectPlane& b) { return a.plane == b.plane; }
bool same_fields(const Coolant& a, const Coolant& b) { return a.change == b.change; }
bool same_fields(const Dwell& a, const Dwell& b) { return a.seconds == b.seconds; }
bool same_fields(const ProgramStop& a, const ProgramStop& b) { return a.optional == b.optional; }
bool same_fields(const ProgramEnd& /*a*/, const ProgramEnd& /*b*/) { return true; }
bool same_fields(const Message& a, const Message& b) { return a.text == b.text; }
bool same_fields(const WorkingFrame& a, const WorkingFrame& b) {
  return a.rotation == b.rotation && a.origin == b.origin;
}
bool same_fields(const CannedCycle& a, const CannedCycle& b) {
  return a.code == b.code && a.x == b.x && a.y == b.y && a.top_z == b.top_z && a.r_z == b.r_z &&
         a.bottom_z == b.bottom_z && a.peck == b.peck && a.dwell_s == b.dwell_s;
}

}  // namespace

bool same_event(const Event& a, const Event& b, bool compare_lines) {
  if (a.index() != b.index()) return false;
  if (compare_lines && source_of(a).line != source_of(b).line) return false;
  return std::visit(
      [&b](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        return same_fields(x, std::get<T>(b));
      },
      a);
}

std::string event_text(const Event& e) {
  std::string text = program::transcript(e);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text;
}

}  // namespace vcpost::verify
