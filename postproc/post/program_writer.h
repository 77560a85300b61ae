// The last stage of the post job: decides the output program block by
// block as the planner declares blocks final, and writes it batch by batch.
// G-code input: the input text with only S/F words changed; Klartext
// input: the input with TOOL CALL S changed or inserted and the blocks
// renumbered (klartext_patch.h); CL input: the program in the profile's
// output format (G-code or Klartext) from the CL events. Internal to the
// post module.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "machines/profile.h"
#include "postproc/gcode/writer.h"
#include "postproc/plan/spindle_plan.h"
#include "postproc/post/path_reader.h"

namespace vcpost::output {
class EventWriter;
}

namespace vcpost::post {

class KlartextPatcher;

// S or F on the control's grid, rounded down so vc (or the feed per tooth)
// never exceeds the planned value.
double on_grid(double value, double step);

class ProgramWriter {
 public:
  // `sink` receives the output in pieces (empty: count the words only).
  // `consumed(offset)`: the writer will not read the text before `offset`
  // again (G-code input), so the caller may release it. `keeps(section)`:
  // the blocks of that tool section keep their S and F as written; asked
  // when a block is written, once its section is decided.
  ProgramWriter(std::string_view text, ProgramKind kind, const machines::MachineProfile& profile,
                bool adjust_feed, std::function<void(std::string_view)> sink,
                std::function<void(std::uint64_t)> consumed,
                std::function<bool(std::uint32_t)> keeps);
  ~ProgramWriter();

  // The blocks (and for CL the events) of a chunk, in program order.
  void add(const Chunk& chunk);
  // The next final plan block, in order, with its coupled feed (when the
  // feed is adjusted): decides every block up to it.
  void on_final(const plan::BlockPlan& plan, const std::optional<plan::BlockFeed>& feed);
  // Writes the blocks decided so far: once per batch of final blocks, not
  // per block (a write of one line costs more than deciding it).
  void flush();
  // After the last final block: writes the rest.
  void finish();

  // The program's S and F in effect on a block still held (not yet written).
  const BlockInfo& block(std::size_t index) const;

  std::uint64_t s_words() const { return s_words_; }
  std::uint64_t f_words() const { return f_words_; }
  // ... written in the blocks of one tool section.
  std::uint64_t s_words(std::uint32_t section) const;
  std::uint64_t f_words(std::uint32_t section) const;
  // Lines that ran more than once and carry a planned S (F): each is
  // written once, with the lowest S (F) in effect at any of its runs,
  // whether that run set it on the line or carried it from a line before
  // (under policy max no run is then faster than vc).
  std::uint64_t repeated_lines() const { return repeated_lines_; }

 private:
  struct Planned {
    const plan::BlockPlan* plan = nullptr;
    const plan::BlockFeed* feed = nullptr;
  };
  // Decides and writes the front block, whose own plan is `own` (or none)
  // and whose next planned block is `next` (or none).
  void resolve_front(Planned own, Planned next);
  // The F the plan couples to this block's S, if any (rapids take none).
  std::optional<double> coupled_feed(const BlockInfo& block, const Planned& own,
                                     const Planned& next);
  void write_text_until(std::uint64_t offset);
  void merge_repeated_patches();
  void flush_cl();
  // The patch that writes speed `rpm` on `block`: an S word, or with the
  // profile's speed output the analog word (gcode::SpeedForm).
  gcode::WordPatch speed_patch(const BlockInfo& block, double rpm) const;

  std::string_view text_;
  ProgramKind kind_;
  bool adjust_feed_;
  double s_step_, f_step_;
  int s_decimals_, f_decimals_;
  std::optional<int> speed_output_;  // output.speed_word "M67 E<n>": n
  std::function<void(std::string_view)> sink_;
  std::function<void(std::uint64_t)> consumed_;
  std::deque<BlockInfo> pending_;
  std::size_t first_pending_ = 0;                              // program index of pending_.front()
  std::deque<std::pair<program::Event, std::size_t>> events_;  // CL
  std::vector<gcode::WordPatch> patches_;  // decided, not yet written (offsets absolute)
  std::uint64_t written_ = 0;              // G-code: text written up to here
  // G-code: lines from here on may run again (Chunk::repeat_from); their
  // text and patches wait for finish().
  std::uint64_t hold_from_ = UINT64_MAX;
  std::uint64_t repeated_lines_ = 0;
  // G-code: the S (F) in effect after the last block decided, as each run
  // plans it (its own words, before the runs of a line share one word);
  // NaN before any. And for each held line (by offset): the lowest S (F)
  // in effect at any of its runs, and how many runs it had. In each run
  // the line's one word holds up to the next line with a word, and up to
  // there the run planned no word of its own: the S it planned there is
  // the one in effect at the line, so the lowest over the runs is safe for
  // all of them.
  struct HeldLine {
    double s = std::numeric_limits<double>::quiet_NaN();
    double f = std::numeric_limits<double>::quiet_NaN();
    std::uint32_t runs = 0;
  };
  double s_in_effect_ = std::numeric_limits<double>::quiet_NaN();
  double f_in_effect_ = std::numeric_limits<double>::quiet_NaN();
  std::unordered_map<std::uint64_t, HeldLine> held_lines_;
  std::ostringstream cl_buffer_;
  std::unique_ptr<output::EventWriter> cl_writer_;
  std::unique_ptr<KlartextPatcher> klartext_;  // Klartext input: TOOL CALL S, numbering
  std::function<bool(std::uint32_t)> keeps_;
  std::uint64_t s_words_ = 0, f_words_ = 0;
  // The S (on the grid) that blocks without motion set since the last block
  // with motion ("S6000 M3" before the first move): a planned word of the
  // same value at the next move would only repeat it, and on a control
  // whose path stops at every S word (LinuxCNC, grbl) cost a stop. NaN: none.
  static constexpr double kNoS = std::numeric_limits<double>::quiet_NaN();
  double s_before_motion_ = kNoS;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> words_by_section_;  // S, F
};

}  // namespace vcpost::post
