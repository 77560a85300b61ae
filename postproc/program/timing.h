// Time along the path: the duration of every event from the programmed feed,
// and the time from program start, for any reader's events (G-code or CL).
//
// The model is the programmed one, without acceleration: a feed move takes
// its path length over its feed rate, a rapid its length over the rapid
// rate, a dwell its seconds, everything else no time. A motion block lasts
// at least the control's block processing time: max(t, block time), not
// t + block time, since a control with look-ahead reads the next blocks
// while it moves, and only blocks shorter than its processing time slow the
// path (MODELS.md section 4). Units: seconds, mm, mm/min, rpm
// (program/events.h).
//   G94 (per_minute):     t = L / F                      [min]
//   G93 (inverse_time):   t = 1 / F                      [min], whatever L
//   G95 (per_revolution): t = L / (F * S)                [min], S the
//                         commanded rpm, the spindle turning (M3/M4)
// L is the straight length, or arc_length() for arcs (helices included).
#pragma once

#include <stdexcept>
#include <string>

#include "core/error.h"
#include "postproc/program/events.h"

namespace vcpost::program {

struct TimingSettings {
  // Path speed of rapids, mm/min, > 0. The machine profile supplies it; the
  // default is a typical small machining centre's.
  double rapid_mm_per_min = 10'000.0;
  // Per motion block processing time of the control, s, >= 0 (0 = none):
  // the shortest time a motion block takes.
  double block_seconds = 0.0;
};

// When an event starts (seconds from program start) and how long it takes.
struct EventTime {
  double start = 0.0;
  double duration = 0.0;
  double end() const { return start + duration; }
};

// A feed move whose duration is undefined: no feed rate in effect (E6101,
// E6102), or a per-revolution feed while the spindle stands still (E6103).
// what() is the message alone; the caller adds the file and line. where()
// holds the move's line and column, with no file (the clock knows none).
class TimingError : public vcpost::Error {
 public:
  TimingError(Code code, const std::string& message, SourceRef source)
      : vcpost::Error(code, message, {"", source.line, source.column}) {}
  // "file:line:col: error[E6101]: message", as the readers word their errors.
  std::string located(const std::string& file) const {
    return format_diagnostic(code(), {file, where().line, where().column}, what());
  }
};

// Follows the feed, feed mode and spindle through the events of one program
// in order and gives each event its time. Starts with no feed (rate 0,
// per_minute) and the spindle stopped.
class PathClock {
 public:
  // Throws std::invalid_argument for rapid_mm_per_min <= 0 or
  // block_seconds < 0 (or either not finite).
  explicit PathClock(TimingSettings settings = {});

  // The time of `event`, which must be the next event of the program.
  // A zero-length move takes the block time. Throws
  // TimingError for a feed move of non-zero length whose time is undefined.
  EventTime advance(const Event& event);

  // Seconds from program start to the end of the last event advanced.
  double elapsed() const { return elapsed_; }
  const TimingSettings& settings() const { return settings_; }

 private:
  double feed_minutes(double length, SourceRef source) const;

  TimingSettings settings_;
  double elapsed_ = 0.0;
  double rate_ = 0.0;
  FeedMode mode_ = FeedMode::per_minute;
  double rpm_ = 0.0;
  bool spindle_turning_ = false;
};

}  // namespace vcpost::program
