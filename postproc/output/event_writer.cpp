#include "postproc/output/event_writer.h"

#include <charconv>
#include <cmath>

#include "postproc/output/gcode_writer.h"
#include "postproc/output/klartext_writer.h"

namespace vcpost::output {

OutputError::OutputError(std::string_view code, const std::string& message,
                         program::SourceRef source)
    : vcpost::Error(code,
                    std::to_string(source.line) + ":" + std::to_string(source.column) + ": error[" +
                        std::string(code) + "]: " + message,
                    {"", source.line, source.column}),
      source_(source) {}

std::string fixed_number(double value, int decimals, const program::SourceRef& source) {
  if (!std::isfinite(value) || std::abs(value) >= 1e9) {
    throw OutputError("E3203", "value cannot be written: " + std::to_string(value), source);
  }
  char buffer[64];
  const auto r =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, decimals);
  std::string s(buffer, r.ptr);
  if (s.find('.') == std::string::npos) s += '.';
  while (s.back() == '0') s.pop_back();
  if (s == "-0.") s = "0.";
  return s;
}

std::unique_ptr<EventWriter> make_event_writer(std::ostream& out,
                                               const machines::MachineProfile& profile) {
  if (profile.output_format() == machines::OutputFormat::heidenhain)
    return std::make_unique<KlartextWriter>(out, klartext_format_for(profile));
  return std::make_unique<GcodeWriter>(out, format_for(profile));
}

void refuse_tilted_frame(const program::WorkingFrame& frame) {
  if (frame.is_identity()) return;
  throw OutputError("E3204",
                    "a tilted working plane (3+2) is not written in the output yet: post the "
                    "tilted set-up's operations from a CL file of their own",
                    frame.source);
}

}  // namespace vcpost::output
