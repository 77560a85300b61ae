#include "postproc/output/klartext_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <type_traits>
#include <variant>

#include "core/text.h"
#include "postproc/output/comment_text.h"
#include "postproc/program/working_frame.h"

namespace vcpost::output {

namespace {

using namespace vcpost::program;

// A fixed number as Klartext writes it: no trailing point ("10", "-0.5").
std::string plain(std::string text) {
  if (text.back() == '.') text.pop_back();
  return text;
}

// ... and a coordinate with its sign, as the TNC's editor writes it ("+10").
std::string signed_text(std::string text) {
  text = plain(std::move(text));
  return text.front() == '-' ? text : "+" + text;
}

}  // namespace

KlartextFormat klartext_format_for(const machines::MachineProfile& profile) {
  const machines::OutputSpec& o = profile.output();
  KlartextFormat format;
  format.program_name = std::to_string(o.program_number);
  format.decimals = o.decimals;
  format.feed_decimals = o.feed_decimals;
  format.coolant_mist = o.coolant_mist;
  format.coolant_flood = o.coolant_flood;
  format.coolant_off = o.coolant_off;
  format.tilted_plane = o.tilted_plane;
  return format;
}

std::optional<Eigen::Vector3d> stock_size(std::string_view message) {
  const std::string upper = to_upper(message);
  const std::size_t at = upper.find("STOCK SIZE");
  if (upper.rfind("INSERT", 0) != 0 || at == std::string::npos) return std::nullopt;
  Eigen::Vector3d size = Eigen::Vector3d::Constant(std::nan(""));
  std::string_view rest = std::string_view(upper).substr(at + 10);
  while (!rest.empty()) {
    const std::size_t start = rest.find_first_not_of(' ');
    if (start == std::string_view::npos) break;
    const std::size_t end = std::min(rest.find(' ', start), rest.size());
    const std::string_view item = rest.substr(start, end - start);
    rest.remove_prefix(end);
    const int axis = item[0] == 'X' ? 0 : item[0] == 'Y' ? 1 : item[0] == 'Z' ? 2 : -1;
    const auto value = finite_number(item.substr(1));
    if (axis < 0 || !value || !(*value > 0)) return std::nullopt;
    size[axis] = *value;
  }
  if (!size.allFinite()) return std::nullopt;
  return size;
}

KlartextWriter::KlartextWriter(std::ostream& out, KlartextFormat format)
    : out_(out), format_(std::move(format)) {}

std::string KlartextWriter::length(double value, const SourceRef& source) const {
  return signed_text(fixed_number(value, format_.decimals, source));
}

void KlartextWriter::block(std::string text) {
  if (!started_) {
    before_start_.push_back(std::move(text));
    return;
  }
  out_ << next_block_++ << ' ' << text << format_.end_of_line;
}

void KlartextWriter::start() {
  started_ = true;
  block("BEGIN PGM " + format_.program_name + " MM");
  if (stock_) {
    const SourceRef none;
    block("BLK FORM 0.1 Z X" + length(0, none) + " Y" + length(0, none) + " Z" +
          length(-stock_->z(), none));
    block("BLK FORM 0.2 X" + length(stock_->x(), none) + " Y" + length(stock_->y(), none) + " Z" +
          length(0, none));
  }
  for (auto& text : before_start_) block(std::move(text));
  before_start_.clear();
}

void KlartextWriter::comment(std::string_view text) {
  if (format_.comments) block("; " + clean_comment(text, CommentEnd::line_end));
}

void KlartextWriter::flush_tool_call() {
  if (!tool_call_) return;
  std::string text = "TOOL CALL " + std::to_string(tool_call_->number) + " Z";
  if (tool_call_->rpm) text += " S" + std::to_string(std::lround(*tool_call_->rpm));
  tool_call_.reset();
  block(std::move(text));
}

void KlartextWriter::axis(std::string& words, char letter, double value, std::string& last,
                          bool force, const SourceRef& source) const {
  std::string text = length(value, source);
  if (!force && text == last) return;
  words += ' ';
  words += letter;
  words += text;
  last = std::move(text);
}

// The F word due on a feed block: the feed set since the last one, where
// it differs from the F in effect (FMAX holds for its own block only).
std::string KlartextWriter::feed_words(const SourceRef& source) {
  if (!pending_feed_) return {};
  std::string f = pending_feed_->per_revolution ? "FU" : "F";
  f += plain(fixed_number(pending_feed_->rate,
                          pending_feed_->per_revolution ? 4 : format_.feed_decimals, source));
  pending_feed_.reset();
  if (f == last_feed_) return {};
  last_feed_ = f;
  return " " + f;
}

void KlartextWriter::motion(const Event& event) {
  flush_tool_call();
  const SourceRef source = source_of(event);
  if (const auto* a = std::get_if<ArcFeed>(&event)) {
    arc(*a);
    return;
  }
  const bool rapid = std::holds_alternative<StraightTraverse>(event);
  const Eigen::Vector3d end =
      written(rapid ? std::get<StraightTraverse>(event).end : std::get<StraightFeed>(event).end);
  std::string words = "L";
  axis(words, 'X', end.x(), last_x_, false, source);
  axis(words, 'Y', end.y(), last_y_, false, source);
  axis(words, 'Z', end.z(), last_z_, false, source);
  if (words.size() == 1) {  // no change: keep one block per move
    axis(words, 'X', end.x(), last_x_, true, source);
    axis(words, 'Y', end.y(), last_y_, true, source);
    axis(words, 'Z', end.z(), last_z_, true, source);
  }
  if (rapid || after_tool_call_) words += " R0";
  words += rapid ? " FMAX" : feed_words(source);
  after_tool_call_ = false;
  block(std::move(words));
}

void KlartextWriter::arc(const ArcFeed& given) {
  ArcFeed a = given;
  a.start = written(a.start);
  a.end = written(a.end);
  a.centre = written(a.centre);
  const SourceRef& source = a.source;
  if (a.plane != Plane::xy) {
    throw OutputError(Code::E3250,
                      "an arc outside the XY plane is not written in Klartext (a TNC takes it "
                      "with the tool axis turned): output the path with arcs in XY or as lines",
                      source);
  }
  block("CC X" + length(a.centre.x(), source) + " Y" + length(a.centre.y(), source));
  const char* direction = a.rotation > 0 ? " DR+" : " DR-";
  const std::string end_z = length(a.end.z(), source);
  const std::string start_z = last_z_.empty() ? length(a.start.z(), source) : last_z_;
  const bool helix = end_z != start_z;
  const bool closed = length(a.end.x(), source) == length(a.start.x(), source) &&
                      length(a.end.y(), source) == length(a.start.y(), source);
  const std::string r0 = after_tool_call_ ? " R0" : "";
  after_tool_call_ = false;
  if (!helix && !closed && std::abs(a.rotation) == 1) {
    std::string words = "C";
    axis(words, 'X', a.end.x(), last_x_, true, source);
    axis(words, 'Y', a.end.y(), last_y_, true, source);
    block(words + direction + r0 + feed_words(source));
    return;
  }
  // Polar, incremental: the angle swept about the pole (the turns the arc
  // starts, the last one to its end) and the rise written as the
  // difference of the two Z the control holds.
  const Eigen::Vector2d from = (a.start - a.centre).head<2>();
  const Eigen::Vector2d to = (a.end - a.centre).head<2>();
  const double turn = 2 * std::numbers::pi;
  double sweep = std::atan2(to.y(), to.x()) - std::atan2(from.y(), from.x());
  if (a.rotation < 0) sweep = -sweep;
  sweep = std::fmod(sweep + 2 * turn, turn);
  if (closed || sweep < 1e-9) sweep = turn;
  sweep += turn * (std::abs(a.rotation) - 1);
  const double degrees = sweep * 180 / std::numbers::pi;
  if (degrees > 5400) {
    throw OutputError(Code::E3252,
                      "a helix of more than 15 turns is not written (a TNC's IPA holds at most "
                      "5400 deg): split it in the CAM system",
                      source);
  }
  std::string words = "CP IPA";
  words += a.rotation > 0 ? "+" : "-";
  words += plain(fixed_number(degrees, 4, source));
  if (helix) {
    const double rise = std::strtod(end_z.c_str(), nullptr) - std::strtod(start_z.c_str(), nullptr);
    words += " IZ" + signed_text(fixed_number(rise, format_.decimals, source));
  }
  last_x_ = length(a.end.x(), source);
  last_y_ = length(a.end.y(), source);
  last_z_ = end_z;
  block(words + direction + r0 + feed_words(source));
}

void KlartextWriter::end_program() {
  if (!started_) start();
  flush_tool_call();
  if (format_.tilted_plane == machines::TiltedPlane::plane_spatial && !frame_.is_identity())
    block("PLANE RESET STAY");
  block("M30");
  block("END PGM " + format_.program_name + " MM");
  ended_ = true;
}

void KlartextWriter::write(const Event& event) {
  if (ended_) return;  // nothing follows END PGM
  std::visit(
      [&](const auto& e) {
        using T = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<T, StraightTraverse> || std::is_same_v<T, StraightFeed> ||
                      std::is_same_v<T, ArcFeed>) {
          if (!started_) start();
          motion(event);
        } else if constexpr (std::is_same_v<T, SetFeedRate>) {
          if (e.mode == FeedMode::inverse_time)
            throw OutputError(Code::E3251, "inverse-time feed is not written in Klartext",
                              e.source);
          pending_feed_ = PendingFeed{e.rate, e.mode == FeedMode::per_revolution};
        } else if constexpr (std::is_same_v<T, SetSpindleSpeed>) {
          // The speed of a tool change goes into its TOOL CALL; any other
          // into a TOOL CALL S of its own (a TNC takes S nowhere else).
          if (tool_call_ && !tool_call_->rpm) {
            tool_call_->rpm = e.rpm;
          } else {
            flush_tool_call();
            block("TOOL CALL S" + std::to_string(std::lround(e.rpm)));
          }
        } else if constexpr (std::is_same_v<T, SpindleOn>) {
          flush_tool_call();
          spindle_on_ = true;
          spindle_ccw_ = e.direction != SpindleDirection::clockwise;
          block(spindle_ccw_ ? "M4" : "M3");
        } else if constexpr (std::is_same_v<T, SpindleOff>) {
          flush_tool_call();
          spindle_on_ = false;
          block("M5");
        } else if constexpr (std::is_same_v<T, SelectTool>) {
          block("TOOL DEF " + std::to_string(e.number));
        } else if constexpr (std::is_same_v<T, ChangeTool>) {
          flush_tool_call();
          tool_call_ = ToolCall{e.number, std::nullopt};
          after_tool_call_ = true;
          spindle_on_ = false;
        } else if constexpr (std::is_same_v<T, CutterCompensation>) {
          if (e.side != compensation_) {
            comment(e.side == CompensationSide::off ? "CUTCOM OFF"
                    : e.side == CompensationSide::left
                        ? "CUTCOM LEFT - CL PATH IS THE TOOL CENTRE"
                        : "CUTCOM RIGHT - CL PATH IS THE TOOL CENTRE");
            compensation_ = e.side;
          }
        } else if constexpr (std::is_same_v<T, Coolant>) {
          flush_tool_call();
          block(e.change == CoolantChange::flood_on  ? format_.coolant_flood
                : e.change == CoolantChange::mist_on ? format_.coolant_mist
                                                     : format_.coolant_off);
        } else if constexpr (std::is_same_v<T, Dwell>) {
          flush_tool_call();
          block("CYCL DEF 9.0 DWELL TIME");
          block("CYCL DEF 9.1 DWELL " + plain(fixed_number(e.seconds, 3, e.source)));
        } else if constexpr (std::is_same_v<T, ProgramStop>) {
          flush_tool_call();
          block(e.optional ? "M1" : "M0");
        } else if constexpr (std::is_same_v<T, ProgramEnd>) {
          end_program();
        } else if constexpr (std::is_same_v<T, Message>) {
          if (!started_ && !stock_) stock_ = stock_size(e.text);
          comment(e.text);
        } else if constexpr (std::is_same_v<T, WorkingFrame>) {
          working_frame(e);
        }
        // ToolLengthOffset (TOOL CALL applies the length), SelectPlane
        // (arcs carry their plane) and CannedCycle (the hole's moves
        // follow) write nothing.
      },
      event);
}

void KlartextWriter::working_frame(const WorkingFrame& frame) {
  if (frame.rotation == frame_.rotation && frame.origin == frame_.origin) return;
  flush_tool_call();
  const SourceRef& src = frame.source;
  if (format_.tilted_plane == machines::TiltedPlane::setup) {
    if (setups_.empty()) setups_.emplace_back();  // the untilted set-up, the first
    const auto at = std::find_if(setups_.begin(), setups_.end(), [&](const WorkingFrame& f) {
      return f.rotation == frame.rotation && f.origin == frame.origin;
    });
    const auto number = static_cast<int>(at - setups_.begin()) + 1;
    if (at == setups_.end()) setups_.push_back(frame);
    const bool turning = spindle_on_;
    if (turning) block("M5");
    comment(setup_instruction(number, frame, "THE PRESET"));
    block("M0");
    if (turning) block(spindle_ccw_ ? "M4" : "M3");
  } else if (frame.is_identity()) {
    block("PLANE RESET STAY");
    shift_.setZero();
  } else {
    const Eigen::Vector3d angles = program::spatial_angles_of(frame.rotation);
    std::string words = "PLANE SPATIAL";
    const char* names[] = {" SPA", " SPB", " SPC"};
    for (int k = 0; k < 3; ++k) words += names[k] + signed_text(fixed_number(angles[k], 4, src));
    block(words + " STAY");
    block("L A+Q120 C+Q122 R0 FMAX");
    shift_ = frame.rotation.transpose() * frame.origin;
  }
  frame_ = frame;
  // Every axis on the next move: the positions are in another frame.
  last_x_.clear();
  last_y_.clear();
  last_z_.clear();
}

void KlartextWriter::finish() {
  if (!ended_) end_program();
  out_.flush();
}

}  // namespace vcpost::output
