// libFuzzer target: `vcpost verify` (lexical and interpreted proofs, G-code
// and CL input) on pairs of programs, and its answer on a program patched
// only in S, which must hold.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz/finding.h"
#include "fuzz/verify_driver.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  (void)vcpost::fuzz::run_verify(text);
  return 0;
}
