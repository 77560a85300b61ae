// The first stage of the post job: reads the program's events and turns
// them into the planner's timeline, chunk by chunk, with the path samples
// still to evaluate. Internal to the post module.
#pragma once

#include <cstdint>
#include <memory>
#include <streambuf>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "machines/profile.h"
#include "postproc/gcode/dialect.h"
#include "postproc/pipeline/point_evaluator.h"
#include "postproc/plan/spindle_plan.h"
#include "postproc/post/post_job.h"
#include "postproc/program/events.h"

namespace vcpost::post {

// An istream buffer over text held elsewhere, without copying it.
class ViewBuffer : public std::streambuf {
 public:
  explicit ViewBuffer(std::string_view text) {
    char* begin = const_cast<char*>(text.data());  // read only: the get area is never written
    setg(begin, begin, begin + text.size());
  }
  std::uint64_t consumed() const { return static_cast<std::uint64_t>(gptr() - eback()); }
};

// What the job remembers of a block of the program until it is written.
struct BlockInfo {
  std::uint64_t offset = 0;  // first byte (G-code) / record (CL)
  bool has_s = false, has_f = false;
  double program_s = 0, program_f = 0;  // in effect on the block
};

enum class SlotKind {
  sample,  // a path sample: evaluated, then its target set
  rapid,   // a rapid move: no target
  resume,  // the start of a move that continues the cut: the last sample's target
};

// One entry of the planner's timeline.
struct Slot {
  SlotKind kind = SlotKind::sample;
  bool break_pass = false;  // a rapid or a tool change comes first: a new pass starts
  plan::Sample plan;        // target and air flag of samples and resumes: set later
  float weight_s = 0;       // cutting time a sample stands for, s
  pipeline::PathSample sample;
};

// A piece of the program, read in one go.
struct Chunk {
  std::vector<Slot> slots;
  // The evaluation of each sample slot, in slot order: filled by the job's
  // stages, not the reader (kept apart from the slots, which are read and
  // written by every stage: a result is five times the size of a slot).
  std::vector<pipeline::PointResult> results;
  std::size_t first_block = 0;    // program index of blocks.front()
  std::vector<BlockInfo> blocks;  // the blocks that start in this chunk
  std::vector<std::pair<program::Event, std::size_t>> events;  // CL input: events, block
  std::size_t samples = 0;                                     // slots of kind sample
  double read_fraction = 0;      // share of the input read when the chunk ends
  std::uint64_t read_bytes = 0;  // bytes of the input read when the chunk ends
};

// Totals the reader counts.
struct ReadTotals {
  std::uint64_t blocks = 0, motion_events = 0;
  double program_time_s = 0, cutting_time_s = 0;
};

class PathReader {
 public:
  // keep_events: also hand out the events (for CL input, whose output is
  // written from them).
  PathReader(std::string_view text, const std::string& file_name, ProgramKind kind,
             const gcode::Dialect& dialect, const machines::MachineProfile& profile,
             double sample_spacing_mm, bool keep_events);
  ~PathReader();

  // Fills `chunk` (cleared first) up to about `samples` path samples, whole
  // blocks only. False when the program has ended and nothing was read.
  // Throws the readers' errors (GcodeError, ClError, TimingError).
  bool read(Chunk& chunk, std::size_t samples);

  const ReadTotals& totals() const { return totals_; }

 private:
  struct State;
  std::unique_ptr<State> state_;
  ReadTotals totals_;
};

}  // namespace vcpost::post
