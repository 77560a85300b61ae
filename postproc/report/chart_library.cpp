#include "postproc/report/chart_library.h"

namespace vcpost::report {

std::string_view chart_library_path() { return VCPOST_CHART_JS; }

}  // namespace vcpost::report
