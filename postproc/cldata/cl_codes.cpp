#include "postproc/cldata/cl_codes.h"

namespace vcpost::cldata {

std::string format(const ClDiagnostic& diagnostic, std::string_view file_name) {
  return format_diagnostic(diagnostic.code,
                           {std::string(file_name), diagnostic.line, diagnostic.column},
                           diagnostic.message);
}

}  // namespace vcpost::cldata
