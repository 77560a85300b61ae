#include "postproc/gcode/diagnostics.h"

namespace vcpost::gcode {

std::string format(const Diagnostic& d, std::string_view file_name) {
  return vcpost::format_diagnostic(d.code, {std::string(file_name), d.line, d.column}, d.message);
}

GcodeError::GcodeError(Diagnostic diagnostic)
    : vcpost::Error(diagnostic.code, format(diagnostic, ""),
                    {"", diagnostic.line, diagnostic.column}),
      diagnostic_(std::move(diagnostic)) {}

}  // namespace vcpost::gcode
