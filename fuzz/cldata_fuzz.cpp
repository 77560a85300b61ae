// libFuzzer target: the APT CL reader (lexer, records, arcs, NURBS, cycles)
// and the timing of its events.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz/cldata_driver.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  (void)vcpost::fuzz::run_cldata(text);
  return 0;
}
