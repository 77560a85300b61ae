// Whether the suite runs under AddressSanitizer (scripts/sanitize.sh's
// preset; GCC defines __SANITIZE_ADDRESS__, clang answers __has_feature).
// There the sanitizers look for memory and undefined-behaviour faults in
// the code a test drives, which a sample of a long brute-force check drives
// as the whole does: the slowest checks then run every kSanitizedStride-th
// case, so the sanitized suite stays within CI's time. The release suite
// runs every case.
#pragma once

namespace vcpost::testing {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif
#else
inline constexpr bool kSanitized = false;
#endif

// Every how many-th case of a long brute-force check runs.
inline constexpr int kSanitizedStride = kSanitized ? 10 : 1;

}  // namespace vcpost::testing
