#include "tests/postproc/codes_in_sources_support.h"

#include <fstream>
#include <iterator>
#include <regex>

namespace vcpost::testing {

std::set<std::string> codes_in_sources(const std::filesystem::path& folder) {
  static const std::regex code_re(R"(\bCode::([EW]\d{4})\b)");
  std::set<std::string> codes;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::path(VCPOST_SOURCE_DIR) / folder)) {
    const auto ext = entry.path().extension();
    if (ext != ".cpp" && ext != ".h") continue;
    std::ifstream in(entry.path(), std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    for (std::sregex_iterator it(text.begin(), text.end(), code_re), end; it != end; ++it)
      codes.insert((*it)[1].str());
  }
  return codes;
}

}  // namespace vcpost::testing
