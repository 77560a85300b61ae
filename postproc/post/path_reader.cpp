#include "postproc/post/path_reader.h"

#include <istream>
#include <optional>
#include <variant>

#include "postproc/cldata/cl_reader.h"
#include "postproc/gcode/interpreter.h"
#include "postproc/pipeline/path_sampler.h"
#include "postproc/program/timing.h"

namespace vcpost::post {
namespace {

using program::Event;

// Reads the events of either kind of program, one batch at a time.
class EventSource {
 public:
  EventSource(std::string_view text, const std::string& file_name, ProgramKind kind,
              const gcode::Dialect& dialect)
      : buffer_(text) {
    if (kind == ProgramKind::gcode) {
      gcode_.emplace(text, dialect);
    } else {
      stream_.emplace(&buffer_);
      cl_.emplace(*stream_, file_name);
    }
  }
  bool next(std::vector<Event>& out) {
    if (gcode_) return gcode_->next(out);
    auto event = cl_->next();
    if (!event) return false;
    out.push_back(std::move(*event));
    return true;
  }
  // Bytes of the text read so far (CL; G-code reports its block offsets).
  std::uint64_t consumed() const { return buffer_.consumed(); }

 private:
  ViewBuffer buffer_;
  std::optional<std::istream> stream_;
  std::optional<gcode::Interpreter> gcode_;
  std::optional<cldata::ClReader> cl_;
};

// Numbers the blocks: a G-code block is a line (its events share a source
// offset); in CL data every motion starts a block, and what comes before
// the first motion is block 0. Takes each event's source and whether it is
// a motion, which the reader looks up once per event.
class BlockCounter {
 public:
  explicit BlockCounter(ProgramKind kind) : kind_(kind) {}
  bool starts_block(const program::SourceRef& source, bool motion) const {
    if (!started_) return true;
    return kind_ == ProgramKind::gcode ? source.offset != last_offset_ : motion;
  }
  // The block of the event, and whether it starts a new one.
  std::pair<std::size_t, bool> on(const program::SourceRef& source, bool motion) {
    const bool fresh = starts_block(source, motion);
    if (fresh && started_) ++block_;
    started_ = true;
    last_offset_ = source.offset;
    return {block_, fresh};
  }

 private:
  ProgramKind kind_;
  bool started_ = false;
  std::size_t block_ = 0;
  std::uint64_t last_offset_ = 0;
};

}  // namespace

struct PathReader::State {
  State(std::string_view program, const std::string& file_name, ProgramKind program_kind,
        const gcode::Dialect& dialect, const machines::MachineProfile& profile, double spacing,
        bool keep)
      : text(program),
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
  bool tool_change = false;    // since the last timeline entry
  bool break_pass = false;     // since the last slot
  std::size_t next_event = 0;  // of `events`, not yet taken
  std::uint64_t last_offset = 0;
};

PathReader::PathReader(std::string_view text, const std::string& file_name, ProgramKind kind,
                       const gcode::Dialect& dialect, const machines::MachineProfile& profile,
                       double sample_spacing_mm, bool keep_events)
    : state_(std::make_unique<State>(text, file_name, kind, dialect, profile, sample_spacing_mm,
                                     keep_events)) {}

PathReader::~PathReader() = default;

bool PathReader::read(Chunk& chunk, std::size_t samples) {
  State& s = *state_;
  chunk.slots.clear();  // keeps its capacity: no allocation per point
  chunk.blocks.clear();
  chunk.events.clear();
  chunk.samples = 0;
  chunk.first_block = totals_.blocks;
  auto next_slot = [&]() -> Slot& {
    Slot& slot = chunk.slots.emplace_back();
    slot.break_pass = s.break_pass;
    s.break_pass = false;
    return slot;
  };

  // A chunk holds whole blocks: it ends before the first event of a block
  // once it has its samples (the rest of the batch waits for the next call).
  bool any = false;
  for (;;) {
    bool more = true;
    while (more && s.next_event == s.events.size()) {  // a block may have no events
      s.events.clear();
      s.next_event = 0;
      more = s.source.next(s.events);
    }
    if (!more) break;
    Event& event = s.events[s.next_event];
    const program::SourceRef source = program::source_of(event);
    const bool motion = program::is_motion(event);
    if (chunk.samples >= samples && s.counter.starts_block(source, motion)) break;
    ++s.next_event;
    any = true;
    const auto [block_index, fresh] = s.counter.on(source, motion);
    if (fresh) {
      chunk.blocks.push_back({source.offset, false, false, s.program_s, s.program_f});
      ++totals_.blocks;
      s.last_offset = chunk.blocks.back().offset;
    }
    BlockInfo& block = chunk.blocks.back();  // a chunk starts with a block
    const program::EventTime time = s.clock.advance(event);
    if (const auto* speed = std::get_if<program::SetSpindleSpeed>(&event)) {
      s.program_s = block.program_s = speed->rpm;
      block.has_s = true;
      if (speed->rpm <= 0) s.spindle = plan::SpindleState::off;
    } else if (const auto* on = std::get_if<program::SpindleOn>(&event)) {
      s.direction = on->direction;
      s.spindle = plan::SpindleState::cw;  // direction applied in spindle_state()
    } else if (std::holds_alternative<program::SpindleOff>(event)) {
      s.spindle = plan::SpindleState::off;
    } else if (const auto* feed = std::get_if<program::SetFeedRate>(&event)) {
      s.program_f = block.program_f = feed->rate;
      block.has_f = true;
    } else if (std::holds_alternative<program::ChangeTool>(event)) {
      s.tool_change = true;
      s.break_pass = true;
    }
    if (motion) {
      ++totals_.motion_events;
      totals_.program_time_s = time.end();
      s.path.clear();
      s.sampler.add(event, totals_.motion_events - 1, s.path);
      if (std::holds_alternative<program::StraightTraverse>(event)) {
        Slot& slot = next_slot();
        slot.kind = SlotKind::rapid;
        slot.break_pass = true;
        slot.plan = {time.start,    block_index,       std::nullopt, true,
                     s.tool_change, s.spindle_state(), s.program_s};
        s.tool_change = false;
      } else {
        totals_.cutting_time_s += time.duration;
        const float weight =
            s.path.empty() ? 0.0f
                           : static_cast<float>(time.duration / static_cast<double>(s.path.size()));
        // The planner holds a block's S from its first sample on: a move
        // that continues the cut starts where the last one ended, at its target.
        if (!s.path.empty() && s.path.front().fraction > 0) {
          Slot& slot = next_slot();
          slot.kind = SlotKind::resume;
          slot.plan = {time.start,    block_index,       std::nullopt, false,
                       s.tool_change, s.spindle_state(), s.program_s};
          s.tool_change = false;
        }
        for (const auto& sample : s.path) {
          Slot& slot = next_slot();
          slot.kind = SlotKind::sample;
          slot.plan = {time.start + time.duration * sample.fraction,
                       block_index,
                       std::nullopt,
                       false,
                       s.tool_change,
                       s.spindle_state(),
                       s.program_s};
          slot.weight_s = weight;
          slot.sample = sample;
          s.tool_change = false;
          ++chunk.samples;
        }
      }
    }
    if (s.keep_events) chunk.events.emplace_back(std::move(event), block_index);
  }
  chunk.read_bytes = s.kind == ProgramKind::gcode ? s.last_offset : s.source.consumed();
  chunk.read_fraction =
      s.text.empty() ? 1.0
                     : static_cast<double>(chunk.read_bytes) / static_cast<double>(s.text.size());
  return any;
}

}  // namespace vcpost::post
