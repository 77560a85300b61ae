// Prints motion events in the vocabulary of LinuxCNC's canonical transcript
// (`rs274 -g`): same call names, argument order and "%.4f" numbers, one call
// per line, so vcpost's reading can be compared with rs274's line by line.
//
// Differences, by design: numbers are always mm / mm/min (rs274 prints in the
// program's units, inches after G20); only the XYZ machine of rs274's default
// build is printed (A, B, C as 0.0000); tool length and cutter compensation
// are printed as rs274's interpreter COMMENTs because vcpost does not know the
// tool table. rs274's leading sequence number and "N....." are not printed.
// Inverse time (G93) is printed as rs274 does: SET_FEED_RATE(F * move length)
// just before each feed move (SetFeedRate::path_rate); an F with no feed move
// in its block becomes a COMMENT (rs274 prints nothing).
#pragma once

#include <string>
#include <string_view>

#include "postproc/program/events.h"

namespace vcpost::program {

struct TranscriptOptions {
  // When true, each line ends with "  # <file>:<line>:<col>" (source_name
  // may be empty: then "# <line>:<col>").
  bool with_source = false;
  std::string_view source_name;
};

// Appends the line(s) for `event` to `out`, each ending in '\n'. Most events
// give one line; Coolant off gives two (MIST_OFF, FLOOD_OFF) as rs274 does.
void append_transcript(std::string& out, const Event& event, const TranscriptOptions& options = {});

// The transcript of a program's events in order: as append_transcript,
// with the motion of a tilted working frame (WorkingFrame) printed where it
// is in the program frame (the machine's positions for the part).
class Transcriber {
 public:
  explicit Transcriber(TranscriptOptions options = {}) : options_(options) {}
  void append(std::string& out, const Event& event);

 private:
  TranscriptOptions options_;
  WorkingFrame frame_;
};

// Convenience: the transcript of one event.
std::string transcript(const Event& event, const TranscriptOptions& options = {});

}  // namespace vcpost::program
