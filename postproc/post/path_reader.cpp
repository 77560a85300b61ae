#include "postproc/post/path_reader.h"

#include <algorithm>
#include <deque>
#include <istream>
#include <optional>
#include <sstream>
#include <variant>

#include "postproc/cldata/cl_reader.h"
#include "postproc/gcode/interpreter.h"
#include "postproc/heidenhain/interpreter.h"
#include "postproc/pipeline/path_sampler.h"
#include "postproc/program/arc.h"
#include "postproc/program/timing.h"
#include "postproc/tools/program_tools.h"

namespace vcpost::post {
namespace {

using program::Event;

// Reads the events of either kind of program, one batch at a time.
class EventSource {
 public:
  EventSource(std::string_view text, const std::string& file_name, ProgramKind kind,
              const gcode::Dialect& dialect)
      : buffer_(text), file_name_(file_name) {
    if (kind == ProgramKind::gcode) {
      gcode_.emplace(text, dialect);
    } else if (kind == ProgramKind::heidenhain) {
      klartext_ = std::make_unique<heidenhain::Interpreter>(text);
    } else {
      stream_.emplace(&buffer_);
      cl_.emplace(*stream_, file_name);
    }
  }
  // The next batch of events; what the program says of its tools on the
  // way (G-code comments, CL cutter records) goes to `tools` first.
  bool next(std::vector<Event>& out, tools::ProgramTools& tools) {
    if (gcode_) {
      if (!gcode_->next(out)) return false;
      const gcode::Block& block = gcode_->block();
      if (!repeat_from_ && may_run_lines_again(block)) repeat_from_ = block.offset;
      for (const gcode::Comment& comment : block.comments) {
        tools.on_comment(comment.text, file_name_ + ":" + std::to_string(block.line),
                         gcode_->state().inches);
      }
      return true;
    }
    if (klartext_) {
      // The tool's radius from its comments or --tool: cycle 208's helix needs it.
      if (const tools::ToolEntry* tool = tools.current(); tool && tool->diameter > 0)
        klartext_->set_tool_radius(tool->diameter / 2);
      if (!klartext_->next(out)) return false;
      const heidenhain::Block& block = klartext_->block();
      repeat_from_ = klartext_->repeat_from();
      for (const heidenhain::Comment& comment : block.comments) {
        tools.on_comment(comment.text, file_name_ + ":" + std::to_string(block.line),
                         klartext_->inches());
      }
      return true;
    }
    auto event = cl_->next();
    while (cutters_seen_ < cl_->cutters().size())
      tools.on_entry(entry_of(cl_->cutters()[cutters_seen_++]));
    if (!event) return false;
    out.push_back(std::move(*event));
    return true;
  }
  void set_program_loader(heidenhain::ProgramLoader loader) {
    if (!klartext_) return;
    klartext_->set_program_loader(std::move(loader));
    klartext_->refuse_tool_calls_in_called_programs();
  }
  std::optional<heidenhain::StockBox> klartext_stock() const {
    return klartext_ ? klartext_->stock() : std::nullopt;
  }
  // Bytes of the text read so far (CL; G-code reports its block offsets).
  std::uint64_t consumed() const { return buffer_.consumed(); }
  // G-code: the reader's warning on lines left unread after the closing '%'
  // (formatted with the file's position), or "".
  std::string unread_after_end() const {
    if (!gcode_) return {};
    for (const gcode::Diagnostic& d : gcode_->warnings())
      if (d.code == vcpost::Code::W1311) return gcode::format(d, file_name_);
    return {};
  }
  // G-code: the line of the first construct after which lines may run
  // more than once (a subroutine, a loop, a call, M98, GOTO), once read.
  std::optional<std::uint64_t> repeat_from() const { return repeat_from_; }

 private:
  static bool may_run_lines_again(const gcode::Block& block) {
    using gcode::ControlKind;
    switch (block.control.kind) {
      case ControlKind::sub:
      case ControlKind::call:
      case ControlKind::while_:
      case ControlKind::do_:
      case ControlKind::repeat:
      case ControlKind::fanuc_goto:
        return true;
      default:
        break;
    }
    return std::ranges::any_of(block.words, [](const auto& word) {
      return (word.letter == 'M' || word.letter == 'm') && word.value == 98;
    });
  }

  std::optional<std::uint64_t> repeat_from_;
  ViewBuffer buffer_;
  std::optional<std::istream> stream_;
  std::optional<gcode::Interpreter> gcode_;
  std::unique_ptr<heidenhain::Interpreter> klartext_;  // held apart: State's layout stays tight
  std::optional<cldata::ClReader> cl_;
  std::string file_name_;
  std::size_t cutters_seen_ = 0;

  // A CL cutter as a tool-table entry: it names no tool number (the
  // LOADTL around it does).
  tools::ToolEntry entry_of(const cldata::ClCutter& cutter) const {
    tools::ToolEntry e;
    e.origin = tools::ToolOrigin::cl_record;
    e.where = file_name_ + ":" + std::to_string(cutter.source.line);
    e.name = cutter.source_word;
    for (std::size_t i = 0; i < cutter.params.size(); ++i) {
      std::ostringstream value;
      value << cutter.params[i];
      e.name += (i == 0 ? "/" : ",") + value.str();
    }
    e.diameter = cutter.diameter();
    if (cutter.tool) {
      switch (cutter.tool->kind) {
        case geometry::ToolKind::ball:
          e.shape = tools::ToolShape::ball;
          break;
        case geometry::ToolKind::bull_nose:
          e.shape = tools::ToolShape::bull_nose;
          break;
        case geometry::ToolKind::flat:
          e.shape = tools::ToolShape::flat;
          break;
      }
      e.diameter = cutter.tool->diameter;
      e.corner_radius = cutter.tool->corner_radius;
    } else {
      e.shape = cutter.source_word.starts_with("TLDATA/DRILL") ? tools::ToolShape::drill
                                                               : tools::ToolShape::other;
    }
    return e;
  }
};

// Whether the last line that is not blank is a '%' (the tape end that
// closes a program as M2/M30 do).
bool ends_with_percent(std::string_view text) {
  const std::size_t last = text.find_last_not_of(" \t\r\n");
  if (last == std::string_view::npos || text[last] != '%') return false;
  const std::size_t line_start = text.find_last_of('\n', last);
  const std::string_view line =
      text.substr(line_start == std::string_view::npos ? 0 : line_start + 1,
                  last + 1 - (line_start == std::string_view::npos ? 0 : line_start + 1));
  return line.find_first_not_of(" \t") == line.size() - 1;
}

// Numbers the blocks: a G-code block is a line (its events share a source
// offset); in CL data every motion starts a block, and so does a tool change
// after the first motion (what follows it belongs to the new tool's
// section); what comes before the first motion is block 0. Takes each
// event's source and whether it is a motion or a tool change, which the
// reader looks up once per event.
class BlockCounter {
 public:
  explicit BlockCounter(ProgramKind kind) : kind_(kind) {}
  bool starts_block(const program::SourceRef& source, bool motion, bool tool_change) const {
    if (!started_) return true;
    if (kind_ != ProgramKind::cldata) return source.offset != last_offset_;
    return motion || (tool_change && moved_);
  }
  // The block of the event, and whether it starts a new one.
  std::pair<std::size_t, bool> on(const program::SourceRef& source, bool motion, bool tool_change) {
    const bool fresh = starts_block(source, motion, tool_change);
    if (fresh && started_) ++block_;
    started_ = true;
    moved_ = moved_ || motion;
    last_offset_ = source.offset;
    return {block_, fresh};
  }

 private:
  ProgramKind kind_;
  bool started_ = false;
  bool moved_ = false;
  std::size_t block_ = 0;
  std::uint64_t last_offset_ = 0;
};

// A junction where the path turns by more than this is a reversal: the
// control must bring the path to rest there whatever its look-ahead
// (cos 170 deg; a 90 deg corner of a zig-zag step-over is blended).
constexpr double kReversalCos = -0.984807753012208;

// Unit directions of a motion at its start and its end; nullopt for a
// move of no length.
std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> motion_directions(const Event& event) {
  auto unit = [](const Eigen::Vector3d& v) -> std::optional<Eigen::Vector3d> {
    const double n = v.norm();
    if (!(n > 1e-12)) return std::nullopt;
    return v / n;
  };
  if (const auto* arc = std::get_if<program::ArcFeed>(&event)) {
    constexpr double du = 1e-6;
    const auto a = unit(program::arc_point(*arc, du) - arc->start);
    const auto b = unit(arc->end - program::arc_point(*arc, 1 - du));
    if (a && b) return std::pair{*a, *b};
    return std::nullopt;
  }
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  if (const auto* f = std::get_if<program::StraightFeed>(&event)) d = f->end - f->start;
  if (const auto* r = std::get_if<program::StraightTraverse>(&event)) d = r->end - r->start;
  if (const auto u = unit(d)) return std::pair{*u, *u};
  return std::nullopt;
}

// Events after which the control has brought the path to rest before the
// next motion: a dwell, a program stop, a spindle command (an S word stops
// the path on the controls where this matters), a tool change.
bool stops_path(const Event& event) {
  return std::holds_alternative<program::Dwell>(event) ||
         std::holds_alternative<program::ProgramStop>(event) ||
         std::holds_alternative<program::SetSpindleSpeed>(event) ||
         std::holds_alternative<program::SpindleOn>(event) ||
         std::holds_alternative<program::SpindleOff>(event) ||
         std::holds_alternative<program::ChangeTool>(event);
}

}  // namespace

struct PathReader::State {
  State(std::string_view program, const std::string& file_name, ProgramKind program_kind,
        const gcode::Dialect& dialect, const machines::MachineProfile& profile, double spacing,
        bool keep, const tools::ToolChoices& tool_choices, double ap)
      : tools(tool_choices),
        ap_mm(ap),
        text(program),
        kind(program_kind),
        source(program, file_name, program_kind, dialect),
        clock({profile.feed().rapid_mm_per_min, profile.control().block_time_s}),
        sampler(spacing),
        counter(program_kind),
        keep_events(keep) {}

  plan::SpindleState spindle_state() const {
    if (spindle == plan::SpindleState::off || program_s <= 0) return plan::SpindleState::off;
    return direction == program::SpindleDirection::clockwise ? plan::SpindleState::cw
                                                             : plan::SpindleState::ccw;
  }

  // The steps of PathReader::read, for one event.
  void note_program_state(const Event& event, BlockInfo& block);
  void decide_section(Chunk& chunk, std::uint32_t line);
  void add_slots(Chunk& chunk, const Event& event, const program::EventTime& time,
                 std::size_t block_index, ReadTotals& totals);
  Slot& next_slot(Chunk& chunk);
  void take_stop(Slot& slot);
  void enter_frame(const program::WorkingFrame& frame);

  const tools::ToolChoices& tools;
  double ap_mm;
  tools::ProgramTools program_tools;
  std::uint32_t section = 0;     // of the events read now
  bool section_decided = false;  // at its first motion
  bool section_posted = false;   // evaluated (postable)
  std::string_view text;
  ProgramKind kind;
  EventSource source;
  program::PathClock clock;
  pipeline::PathSampler sampler;
  BlockCounter counter;
  bool keep_events;
  std::vector<Event> events;
  std::vector<pipeline::PathSample> path;
  plan::SpindleState spindle = plan::SpindleState::off;
  program::SpindleDirection direction = program::SpindleDirection::clockwise;
  double program_s = 0, program_f = 0;
  bool tool_change = false;  // since the last timeline entry
  bool break_pass = false;   // since the last slot
  bool path_stops = false;   // the path stops before the next slot (Sample::path_stops)
  std::optional<Eigen::Vector3d> last_direction;  // of the last motion of non-zero length
  std::size_t next_event = 0;                     // of `events`, not yet taken
  std::uint64_t last_offset = 0;
  bool program_end = false;  // M2/M30 (a ProgramEnd event) read
  // Every tilted frame met (a deque: the samples point into it) and the
  // one in effect (null: untilted).
  std::deque<geometry::RigidTransform> frames;
  const geometry::RigidTransform* placement = nullptr;
};

PathReader::PathReader(std::string_view text, const std::string& file_name, ProgramKind kind,
                       const gcode::Dialect& dialect, const machines::MachineProfile& profile,
                       double sample_spacing_mm, bool keep_events, const tools::ToolChoices& tools,
                       double ap_mm)
    : state_(std::make_unique<State>(text, file_name, kind, dialect, profile, sample_spacing_mm,
                                     keep_events, tools, ap_mm)) {}

PathReader::~PathReader() = default;

void PathReader::set_program_loader(heidenhain::ProgramLoader loader) {
  state_->source.set_program_loader(std::move(loader));
}

std::optional<heidenhain::StockBox> PathReader::klartext_stock() const {
  return state_->source.klartext_stock();
}

const std::vector<std::string>& PathReader::tool_notes() const {
  return state_->program_tools.notes();
}

Slot& PathReader::State::next_slot(Chunk& chunk) {
  Slot& slot = chunk.slots.emplace_back();
  slot.break_pass = break_pass;
  slot.section = section;
  break_pass = false;
  return slot;
}

// The first slot after a stop of the path carries it.
void PathReader::State::take_stop(Slot& slot) {
  slot.plan.path_stops = path_stops;
  path_stops = false;
}

// The program's own S, F, spindle, end and tool change, as they stand.
void PathReader::State::note_program_state(const Event& event, BlockInfo& block) {
  if (const auto* speed = std::get_if<program::SetSpindleSpeed>(&event)) {
    program_s = block.program_s = speed->rpm;
    block.has_s = true;
    if (speed->rpm <= 0) spindle = plan::SpindleState::off;
  } else if (const auto* on = std::get_if<program::SpindleOn>(&event)) {
    direction = on->direction;
    spindle = plan::SpindleState::cw;  // direction applied in spindle_state()
  } else if (std::holds_alternative<program::SpindleOff>(event)) {
    spindle = plan::SpindleState::off;
  } else if (const auto* feed = std::get_if<program::SetFeedRate>(&event)) {
    program_f = block.program_f = feed->rate;
    block.has_f = true;
  } else if (std::holds_alternative<program::ProgramEnd>(event)) {
    program_end = true;
  } else if (std::holds_alternative<program::ChangeTool>(event)) {
    tool_change = true;
    break_pass = true;
  } else if (const auto* frame = std::get_if<program::WorkingFrame>(&event)) {
    enter_frame(*frame);
  }
}

// A tilted working plane: the samples that follow are in its coordinates
// and carry the placement of the model in them (one kept per distinct frame).
void PathReader::State::enter_frame(const program::WorkingFrame& frame) {
  break_pass = true;
  path_stops = true;  // the machine turns its rotary axes between the two
  last_direction.reset();
  if (frame.is_identity()) {
    placement = nullptr;
    return;
  }
  const geometry::RigidTransform turned =
      geometry::RigidTransform{frame.rotation, frame.origin}.inverse();
  for (const geometry::RigidTransform& known : frames) {
    if (known.rotation == turned.rotation && known.shift == turned.shift) {
      placement = &known;
      return;
    }
  }
  placement = &frames.emplace_back(turned);
}

// At a section's first motion: which tool cuts it and whether it is posted.
void PathReader::State::decide_section(Chunk& chunk, std::uint32_t line) {
  program_tools.on_motion();
  if (section_decided) return;
  const auto number = program_tools.number();
  const tools::ToolEntry* tool = tools.table.resolve(number, program_tools.current());
  chunk.sections.push_back(post::decide_section(section, number, line, tool, tools, ap_mm));
  section_posted = chunk.sections.back().postable;
  section_decided = true;
}

// A motion's slots: one for a rapid; else a resume where the move continues
// the cut, then its samples.
void PathReader::State::add_slots(Chunk& chunk, const Event& event, const program::EventTime& time,
                                  std::size_t block_index, ReadTotals& totals) {
  path.clear();
  sampler.add(event, totals.motion_events - 1, path);
  if (placement != nullptr)
    for (pipeline::PathSample& sample : path) sample.frame = placement;
  if (std::holds_alternative<program::StraightTraverse>(event)) {
    Slot& slot = next_slot(chunk);
    slot.kind = SlotKind::rapid;
    slot.break_pass = true;
    slot.plan = {time.start,  block_index, std::nullopt,    true,
                 tool_change, false,       spindle_state(), program_s};
    take_stop(slot);
    tool_change = false;
    return;
  }
  totals.cutting_time_s += time.duration;
  const float weight =
      path.empty() ? 0.0f : static_cast<float>(time.duration / static_cast<double>(path.size()));
  // The planner holds a block's S from its first sample on: a move that
  // continues the cut starts where the last one ended, at its target.
  if (!path.empty() && path.front().fraction > 0) {
    Slot& slot = next_slot(chunk);
    slot.kind = SlotKind::resume;
    slot.plan = {time.start,  block_index, std::nullopt,    false,
                 tool_change, false,       spindle_state(), program_s};
    take_stop(slot);
    tool_change = false;
  }
  for (const auto& sample : path) {
    Slot& slot = next_slot(chunk);
    slot.kind = section_posted ? SlotKind::sample : SlotKind::kept;
    slot.plan = {time.start + time.duration * sample.fraction,
                 block_index,
                 std::nullopt,
                 false,
                 tool_change,
                 false,
                 spindle_state(),
                 program_s};
    take_stop(slot);
    slot.weight_s = weight;
    slot.sample = sample;
    tool_change = false;
    ++chunk.samples;
  }
}

bool PathReader::read(Chunk& chunk, std::size_t samples) {
  State& s = *state_;
  chunk.slots.clear();  // keeps its capacity: no allocation per point
  chunk.blocks.clear();
  chunk.events.clear();
  chunk.samples = 0;
  chunk.sections.clear();
  chunk.first_section = s.section;
  chunk.first_block = totals_.blocks;

  // A chunk holds whole blocks: it ends before the first event of a block
  // once it has its samples (the rest of the batch waits for the next call).
  bool any = false;
  for (;;) {
    bool more = true;
    while (more && s.next_event == s.events.size()) {  // a block may have no events
      s.events.clear();
      s.next_event = 0;
      more = s.source.next(s.events, s.program_tools);
    }
    if (!more) {
      totals_.missing_end =
          s.kind == ProgramKind::gcode && !s.program_end && !ends_with_percent(s.text);
      totals_.unread_after_end = s.source.unread_after_end();
      if (!totals_.unread_after_end.empty()) totals_.missing_end = false;
      break;
    }
    Event& event = s.events[s.next_event];
    const program::SourceRef source = program::source_of(event);
    const bool motion = program::is_motion(event);
    const auto* change = std::get_if<program::ChangeTool>(&event);
    if (chunk.samples >= samples && s.counter.starts_block(source, motion, change)) break;
    ++s.next_event;
    any = true;
    if (change) {
      // A new section: its tool is decided at its first motion.
      s.program_tools.on_tool_change(change->number);
      ++s.section;
      s.section_decided = false;
    }
    const auto [block_index, fresh] = s.counter.on(source, motion, change);
    if (fresh) {
      chunk.blocks.push_back({source.offset, false, false, s.program_s, s.program_f, s.section,
                              s.spindle_state() != plan::SpindleState::off});
      ++totals_.blocks;
      s.last_offset = chunk.blocks.back().offset;
    }
    BlockInfo& block = chunk.blocks.back();  // a chunk starts with a block
    if (change) block.section = s.section;   // the tool-change block is the new tool's
    const program::EventTime time = s.clock.advance(event);
    if (stops_path(event)) s.path_stops = true;
    s.note_program_state(event, block);
    if (motion) {
      if (const auto directions = motion_directions(event)) {
        if (s.last_direction && s.last_direction->dot(directions->first) < kReversalCos)
          s.path_stops = true;
        s.last_direction = directions->second;
      }
      s.decide_section(chunk, source.line);
      ++totals_.motion_events;
      totals_.program_time_s = time.end();
      s.add_slots(chunk, event, time, block_index, totals_);
    }
    if (s.keep_events) chunk.events.emplace_back(std::move(event), block_index);
  }
  chunk.read_bytes = s.kind != ProgramKind::cldata ? s.last_offset : s.source.consumed();
  chunk.repeat_from = s.source.repeat_from();
  chunk.read_fraction =
      s.text.empty() ? 1.0
                     : static_cast<double>(chunk.read_bytes) / static_cast<double>(s.text.size());
  return any;
}

}  // namespace vcpost::post
