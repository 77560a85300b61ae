#include "vcpost/version.h"

#include "vcpost_revision.h"  // generated at build time (cmake/write_revision.cmake)

namespace vcpost::api {

const char* version() { return VCPOST_VERSION; }

const char* revision() { return VCPOST_GIT_REVISION; }

std::string version_line() {
  std::string line = std::string("vcpost ") + version();
  if (*revision() != '\0') line += std::string(" (git ") + revision() + ")";
  return line;
}

}  // namespace vcpost::api
