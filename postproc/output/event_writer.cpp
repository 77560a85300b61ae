#include "postproc/output/event_writer.h"

#include <charconv>
#include <cmath>

#include "postproc/output/gcode_writer.h"
#include "postproc/output/klartext_writer.h"

namespace vcpost::output {

OutputError::OutputError(Code code, const std::string& message, program::SourceRef source)
    : vcpost::Error(code, format_diagnostic(code, {"", source.line, source.column}, message),
                    {"", source.line, source.column}),
      source_(source) {}

std::string fixed_number(double value, int decimals, const program::SourceRef& source) {
  if (!std::isfinite(value) || std::abs(value) >= 1e9) {
    throw OutputError(Code::E3203, "value cannot be written: " + std::to_string(value), source);
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

namespace {

// A direction or point in the part's frame, "(1, 0, -0.7071)".
std::string triple(const Eigen::Vector3d& v, int decimals) {
  std::string text = "(";
  for (int k = 0; k < 3; ++k) {
    std::string n = fixed_number(v[k], decimals, {});
    if (n.back() == '.') n.pop_back();
    text += (k ? ", " : "") + n;
  }
  return text + ")";
}

}  // namespace

std::string setup_instruction(int number, const program::WorkingFrame& frame,
                              std::string_view offset) {
  std::string text = "SET-UP " + std::to_string(number) + ": ";
  if (frame.is_identity()) {
    text += "CLAMP THE PART AS AT THE START (ITS +Z UP, ITS +X ALONG +X)";
  } else {
    text += "CLAMP THE PART WITH ITS DIRECTION " + triple(frame.rotation.col(2), 4) +
            " UP THE SPINDLE (+Z) AND ITS " + triple(frame.rotation.col(0), 4) + " ALONG +X";
  }
  text += ", SET ";
  text += offset;
  text += " ON ITS POINT " + triple(frame.origin, 4) + ", THEN CYCLE START";
  return text;
}

}  // namespace vcpost::output
