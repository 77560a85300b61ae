// libFuzzer target: the machine-profile loader (TOML text -> MachineProfile)
// and the round trip of a valid profile through profile_to_toml.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz/profile_driver.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  (void)vcpost::fuzz::run_profile(text);
  return 0;
}
