// What the post job writes CL data through: a program writer that takes the
// motion events one by one, in the language of the machine's profile
// (machine.output_format): G-code (gcode_writer.h) or Heidenhain Klartext
// (klartext_writer.h).
#pragma once

#include <memory>
#include <ostream>
#include <string>
#include <string_view>

#include "core/error.h"
#include "machines/profile.h"
#include "postproc/program/events.h"

namespace vcpost::output {

// Errors of the writers: E3201 arc of more than one turn (G-code), E3202
// inverse-time feed, E3203 number that cannot be written (not finite or
// too large); Klartext: E3250, E3251, E3252 (klartext_writer.h).
class OutputError : public vcpost::Error {
 public:
  OutputError(Code code, const std::string& message, program::SourceRef source);
  const program::SourceRef& source() const { return source_; }

 private:
  program::SourceRef source_;
};

// `value` with `decimals` digits after the point, trailing zeros dropped,
// the point kept ("10.", "-0.5", "0."; never "-0."). Throws OutputError
// E3203 for a value that is not finite or 1e9 or more in size.
std::string fixed_number(double value, int decimals, const program::SourceRef& source);

// The comment of a set-up (profile output.tilted_plane "setup"): how the
// operator clamps the part so that the frame's z points up the spindle and
// its x along the machine's +X, and which point of the part the work offset
// `offset` ("G55", or a Klartext preset) is set on. `number` counts from 1.
std::string setup_instruction(int number, const program::WorkingFrame& frame,
                              std::string_view offset);

class EventWriter {
 public:
  virtual ~EventWriter() = default;
  // Appends the blocks of one event. Throws OutputError (gcode_writer.h)
  // for an event the language cannot express.
  virtual void write(const program::Event& event) = 0;
  // Ends the program unless a ProgramEnd event already did.
  virtual void finish() = 0;
};

// The writer of the profile's output format, writing to `out` (which must
// outlive it).
std::unique_ptr<EventWriter> make_event_writer(std::ostream& out,
                                               const machines::MachineProfile& profile);

}  // namespace vcpost::output
