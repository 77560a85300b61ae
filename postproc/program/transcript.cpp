#include "postproc/program/transcript.h"

#include <charconv>
#include <cmath>
#include <system_error>

#include "postproc/program/arc.h"

namespace vcpost::program {

namespace {

// "%.4f" as printf gives it (including "-0.0000"), without locale.
void append_number(std::string& out, double value) {
  char buffer[64];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, 4);
  if (result.ec == std::errc()) {
    out.append(buffer, result.ptr);
  } else {
    out += "nan";  // only for values too large for 64 characters
  }
}

void append_int(std::string& out, long long value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

void append_xyz(std::string& out, const Eigen::Vector3d& p) {
  append_number(out, p.x());
  out += ", ";
  append_number(out, p.y());
  out += ", ";
  append_number(out, p.z());
  out += ", 0.0000, 0.0000, 0.0000)";
}

const char* plane_name(Plane plane) {
  switch (plane) {
    case Plane::xy:
      return "CANON_PLANE_XY";
    case Plane::xz:
      return "CANON_PLANE_XZ";
    case Plane::yz:
      return "CANON_PLANE_YZ";
  }
  return "CANON_PLANE_XY";
}

void append_quoted(std::string& out, std::string_view name, std::string_view text) {
  out += name;
  out += "(\"";
  out += text;
  out += "\")";
}

// The canonical call of each kind of event, as rs274 prints it.
void append_call_of(std::string& out, const StraightTraverse& e) {
  out += "STRAIGHT_TRAVERSE(";
  append_xyz(out, e.end);
}

void append_call_of(std::string& out, const StraightFeed& e) {
  out += "STRAIGHT_FEED(";
  append_xyz(out, e.end);
}

void append_call_of(std::string& out, const ArcFeed& e) {
  const auto ax = plane_axes(e.plane);
  out += "ARC_FEED(";
  append_number(out, e.end[ax[0]]);
  out += ", ";
  append_number(out, e.end[ax[1]]);
  out += ", ";
  append_number(out, e.centre[ax[0]]);
  out += ", ";
  append_number(out, e.centre[ax[1]]);
  out += ", ";
  append_int(out, e.rotation);
  out += ", ";
  append_number(out, e.end[ax[2]]);
  out += ", 0.0000, 0.0000, 0.0000)";
}

void append_call_of(std::string& out, const SetFeedRate& e) {
  if (e.mode == FeedMode::inverse_time && !e.path_rate) {
    // rs274 prints nothing for an F that moves nothing in G93.
    out += "COMMENT(\"interpreter: inverse-time feed ";
    append_number(out, e.rate);
    out += " with no feed move\")";
  } else {
    out += "SET_FEED_RATE(";
    append_number(out, e.mode == FeedMode::inverse_time ? *e.path_rate : e.rate);
    out += ')';
  }
}

void append_call_of(std::string& out, const SetSpindleSpeed& e) {
  out += "SET_SPINDLE_SPEED(0, ";
  append_number(out, e.rpm);
  out += ')';
}

void append_call_of(std::string& out, const SpindleOn& e) {
  out += e.direction == SpindleDirection::clockwise ? "START_SPINDLE_CLOCKWISE(0)"
                                                    : "START_SPINDLE_COUNTERCLOCKWISE(0)";
}

void append_call_of(std::string& out, const SpindleOff& /*e*/) { out += "STOP_SPINDLE_TURNING(0)"; }

void append_call_of(std::string& out, const SelectTool& e) {
  out += "SELECT_TOOL(";
  append_int(out, e.number);
  out += ')';
}

void append_call_of(std::string& out, const ChangeTool& e) {
  out += "CHANGE_TOOL(";
  append_int(out, e.number);
  out += ')';
}

void append_call_of(std::string& out, const ToolLengthOffset& e) {
  std::string text =
      e.enabled ? "interpreter: tool length offset on" : "interpreter: tool length offset off";
  if (e.enabled && e.register_number) {
    text += " H";
    append_int(text, *e.register_number);
  }
  append_quoted(out, "COMMENT", text);
}

void append_call_of(std::string& out, const CutterCompensation& e) {
  append_quoted(out, "COMMENT",
                e.side == CompensationSide::off ? "interpreter: cutter radius compensation off"
                : e.side == CompensationSide::left
                    ? "interpreter: cutter radius compensation on left"
                    : "interpreter: cutter radius compensation on right");
}

void append_call_of(std::string& out, const SelectPlane& e) {
  out += "SELECT_PLANE(";
  out += plane_name(e.plane);
  out += ')';
}

void append_call_of(std::string& out, const Coolant& e) {
  out += e.change == CoolantChange::mist_on    ? "MIST_ON()"
         : e.change == CoolantChange::flood_on ? "FLOOD_ON()"
                                               : "MIST_OFF()\nFLOOD_OFF()";
}

void append_call_of(std::string& out, const Dwell& e) {
  out += "DWELL(";
  append_number(out, e.seconds);
  out += ')';
}

void append_call_of(std::string& out, const ProgramStop& e) {
  out += e.optional ? "OPTIONAL_PROGRAM_STOP()" : "PROGRAM_STOP()";
}

void append_call_of(std::string& out, const ProgramEnd& /*e*/) { out += "PROGRAM_END()"; }

void append_call_of(std::string& out, const Message& e) { append_quoted(out, "MESSAGE", e.text); }

// Not a call of rs274's (it has no tilted plane): the frame's origin, then
// its x and z axes (z: the tool axis) in the program frame.
void append_call_of(std::string& out, const WorkingFrame& e) {
  out += "SET_WORKING_FRAME(";
  append_number(out, e.origin.x());
  for (const double v : {e.origin.y(), e.origin.z(), e.rotation(0, 0), e.rotation(1, 0),
                         e.rotation(2, 0), e.rotation(0, 2), e.rotation(1, 2), e.rotation(2, 2)}) {
    out += ", ";
    append_number(out, v);
  }
  out += ')';
}

// rs274 prints a cycle's moves, which follow the marker, not the cycle
// (append_transcript leaves it out).
void append_call_of(std::string& /*out*/, const CannedCycle& /*e*/) {}

// Writes the call(s) without the trailing newline; lines are separated by
// '\n' and the caller adds the source suffix to each.
void append_call(std::string& out, const Event& event) {
  std::visit([&out](const auto& e) { append_call_of(out, e); }, event);
}

void append_source(std::string& out, const SourceRef& source, const TranscriptOptions& options) {
  out += "  # ";
  if (!options.source_name.empty()) {
    out += options.source_name;
    out += ':';
  }
  append_int(out, source.line);
  out += ':';
  append_int(out, source.column);
}

}  // namespace

void append_transcript(std::string& out, const Event& event, const TranscriptOptions& options) {
  // rs274 prints a cycle's moves, which follow the marker, not the cycle.
  if (std::holds_alternative<CannedCycle>(event)) return;
  const std::size_t start = out.size();
  append_call(out, event);
  if (options.with_source) {
    const SourceRef source = source_of(event);
    // Only Coolant off prints two calls; each line gets the suffix.
    if (const auto newline = out.find('\n', start); newline != std::string::npos) {
      std::string suffix;
      append_source(suffix, source, options);
      out.insert(newline, suffix);
    }
    append_source(out, source, options);
  }
  out += '\n';
}

namespace {

// A motion of a tilted frame turned into the program frame. An arc whose
// axis is a principal axis there stays an ARC_FEED in that plane; any
// other prints as ARC_FEED_3D (end, centre, axis, turns), which rs274 has
// not.
Event to_program_frame(const Event& event, const WorkingFrame& frame) {
  Event out = event;
  if (auto* t = std::get_if<StraightTraverse>(&out)) {
    t->start = frame.to_program(t->start);
    t->end = frame.to_program(t->end);
  } else if (auto* f = std::get_if<StraightFeed>(&out)) {
    f->start = frame.to_program(f->start);
    f->end = frame.to_program(f->end);
  }
  return out;
}

void append_tilted_arc(std::string& out, const ArcFeed& arc, const WorkingFrame& frame) {
  const auto ax = plane_axes(arc.plane);
  Eigen::Vector3d centre = arc.centre;
  centre[ax[2]] = arc.start[ax[2]];
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();
  axis[ax[2]] = arc.rotation > 0 ? 1.0 : -1.0;
  const Eigen::Vector3d end = frame.to_program(arc.end);
  const Eigen::Vector3d c = frame.to_program(centre);
  axis = frame.rotation * axis;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(std::abs(axis[k]) - 1.0) > 1e-12) continue;
    ArcFeed turned = arc;
    turned.plane = k == 2 ? Plane::xy : k == 1 ? Plane::xz : Plane::yz;
    turned.rotation = axis[k] > 0 ? std::abs(arc.rotation) : -std::abs(arc.rotation);
    turned.start = frame.to_program(arc.start);
    turned.end = end;
    turned.centre = c;
    append_call(out, turned);
    return;
  }
  out += "ARC_FEED_3D(";
  append_number(out, end.x());
  for (const double v : {end.y(), end.z(), c.x(), c.y(), c.z(), axis.x(), axis.y(), axis.z()}) {
    out += ", ";
    append_number(out, v);
  }
  out += ", ";
  append_int(out, std::abs(arc.rotation));
  out += ')';
}

}  // namespace

void Transcriber::append(std::string& out, const Event& event) {
  if (const auto* frame = std::get_if<WorkingFrame>(&event)) {
    frame_ = *frame;
    append_transcript(out, event, options_);
    return;
  }
  if (frame_.is_identity() || !is_motion(event)) {
    append_transcript(out, event, options_);
    return;
  }
  if (const auto* arc = std::get_if<ArcFeed>(&event)) {
    append_tilted_arc(out, *arc, frame_);
    if (options_.with_source) append_source(out, arc->source, options_);
    out += '\n';
    return;
  }
  append_transcript(out, to_program_frame(event, frame_), options_);
}

std::string transcript(const Event& event, const TranscriptOptions& options) {
  std::string out;
  append_transcript(out, event, options);
  return out;
}

}  // namespace vcpost::program
