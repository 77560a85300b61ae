#include "postproc/heidenhain/diagnostics.h"

namespace vcpost::heidenhain {

std::string format(const Diagnostic& d, std::string_view file_name) {
  return vcpost::format_diagnostic(
      d.code, {d.file.empty() ? std::string(file_name) : d.file, d.line, d.column}, d.message);
}

KlartextError::KlartextError(Diagnostic diagnostic)
    : vcpost::Error(diagnostic.code, format(diagnostic, ""),
                    {diagnostic.file, diagnostic.line, diagnostic.column}),
      diagnostic_(std::move(diagnostic)) {}

}  // namespace vcpost::heidenhain
