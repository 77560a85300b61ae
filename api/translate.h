// How the facade turns the internals' failures into the one public
// vcpost::api::Error: every call of <vcpost/...> runs inside guarded().
#pragma once

#include <exception>
#include <string>
#include <utility>

#include "vcpost/error.h"

namespace vcpost::api {

// The Error for an internal message in the command line's format,
// "file:line:col: error[E1201]: message" (position and code each optional).
Error error_from_message(const std::string& what);

// Runs `work`; anything it throws but an Error leaves as an Error.
template <class Work>
auto guarded(Work&& work) -> decltype(work()) {
  try {
    return std::forward<Work>(work)();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw error_from_message(e.what());
  }
}

}  // namespace vcpost::api
