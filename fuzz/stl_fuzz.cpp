// libFuzzer target: the STL reader (binary and ASCII).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz/stl_driver.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  (void)vcpost::fuzz::run_stl(bytes);
  return 0;
}
