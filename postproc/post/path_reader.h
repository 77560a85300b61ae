// The first stage of the post job: reads the program's events and turns
// them into the planner's timeline, chunk by chunk, with the path samples
// still to evaluate. Internal to the post module.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <streambuf>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "machines/profile.h"
#include "postproc/gcode/dialect.h"
#include "postproc/heidenhain/interpreter.h"
#include "postproc/heidenhain/program_loader.h"
#include "postproc/pipeline/point_evaluator.h"
#include "postproc/plan/spindle_plan.h"
#include "postproc/post/post_job.h"
#include "postproc/post/tool_sections.h"
#include "postproc/program/events.h"
#include "postproc/tools/tool_table.h"

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
  std::uint32_t section = 0;            // the tool section it belongs to (ToolSection::index)
  // The spindle turns before the block (on, with a speed above 0): a speed
  // word here changes a running spindle; else it is the spindle's start.
  bool spindle_turns = false;
};

enum class SlotKind : std::uint8_t {
  sample,  // a path sample: evaluated, then its target set
  rapid,   // a rapid move: no target
  resume,  // the start of a move that continues the cut: the last sample's target
  kept,    // a path sample of a section the job does not post: not evaluated
};

// One entry of the planner's timeline.
struct Slot {
  SlotKind kind = SlotKind::sample;
  bool break_pass = false;    // a rapid or a tool change comes first: a new pass starts
  std::uint32_t section = 0;  // ToolSection::index
  plan::Sample plan;          // target and air flag of samples and resumes: set later
  float weight_s = 0;         // cutting time a sample stands for, s
  pipeline::PathSample sample;
};

// Path samples per chunk: the unit of work of the post's threads. Contact
// queries start cold at every chunk (so results do not depend on the
// number of threads), which costs little at this size.
inline constexpr std::size_t chunk_samples = 2048;

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
  std::size_t samples = 0;                                     // slots of kind sample or kept
  // The program's count of sample slots before this chunk's first (set by
  // the job: the index of its normals from the toolpath).
  std::uint64_t first_sample = 0;
  // Sections whose first motion is in this chunk, decided by the reader.
  std::vector<ToolSection> sections;
  // The evaluator of each section its slots name, from first_section on
  // (null for sections not posted): set by the job before the chunk is
  // evaluated, read by the stages on other threads.
  std::uint32_t first_section = 0;
  std::vector<pipeline::PointEvaluator*> evaluators;
  pipeline::PointEvaluator* evaluator(std::uint32_t section) const {
    return evaluators[section - first_section];
  }
  double read_fraction = 0;      // share of the input read when the chunk ends
  std::uint64_t read_bytes = 0;  // bytes of the input read when the chunk ends
  // G-code: from this offset on, lines may run more than once (subroutines,
  // loops, M98): the writer holds them until every run has its S.
  std::optional<std::uint64_t> repeat_from;
};

// Totals the reader counts.
struct ReadTotals {
  std::uint64_t blocks = 0, motion_events = 0;
  double program_time_s = 0, cutting_time_s = 0;
  bool missing_end = false;  // G-code without M2/M30 or closing '%'
  // G-code: the warning on lines after the closing '%', which are neither
  // read nor posted ("" when there are none).
  std::string unread_after_end;
};

class PathReader {
 public:
  // keep_events: also hand out the events (for CL input, whose output is
  // written from them). `tools` decides every section's tool at its first
  // motion, with what the program says (comments, CL cutters); ap_mm is
  // checked against each posted tool's diameter.
  PathReader(std::string_view text, const std::string& file_name, ProgramKind kind,
             const gcode::Dialect& dialect, const machines::MachineProfile& profile,
             double sample_spacing_mm, bool keep_events, const tools::ToolChoices& tools,
             double ap_mm);
  ~PathReader();
  // Klartext: how CALL PGM finds the called program; a TOOL CALL in one is
  // refused (the writer changes the main program's blocks only).
  void set_program_loader(heidenhain::ProgramLoader loader);

  // Fills `chunk` (cleared first) up to about `samples` path samples, whole
  // blocks only. False when the program has ended and nothing was read.
  // Throws the readers' errors (GcodeError, ClError, TimingError).
  bool read(Chunk& chunk, std::size_t samples);

  const ReadTotals& totals() const { return totals_; }
  // Klartext: the stock box its BLK FORM declared (read so far).
  std::optional<heidenhain::StockBox> klartext_stock() const;
  // Notes on tool comments that could not be read, in file order.
  const std::vector<std::string>& tool_notes() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
  ReadTotals totals_;
};

}  // namespace vcpost::post
