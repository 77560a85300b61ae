// libFuzzer target: G-code tokenizer, interpreter, timing and S/F writer, in
// the three dialects (rs274ngc, Fanuc, Mazak) on every input.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz/gcode_driver.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  (void)vcpost::fuzz::run_gcode_all_dialects(text);
  return 0;
}
