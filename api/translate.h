// How the facade turns the internals' failures into the one public
// vcpost::api::Error: every call of <vcpost/...> runs inside guarded().
#pragma once

#include <exception>
#include <string>
#include <utility>

#include "core/error.h"
#include "vcpost/error.h"

namespace vcpost::api {

// The Error for an internal message in the command line's format,
// "file:line:col: error[E1201]: message" (position and code each optional).
Error error_from_message(const std::string& what);

// The Error for one of vcpost's own: its code, hint, severity and place as
// it carries them; `program_file` names the file of a place that has a
// line but no file (the readers' errors: the text they read has no name).
Error error_from(const vcpost::Error& error, const std::string& program_file);

// Runs `work`; anything it throws but an Error leaves as an Error.
template <class Work>
auto guarded(Work&& work, const std::string& program_file = {}) -> decltype(work()) {
  try {
    return std::forward<Work>(work)();
  } catch (const Error&) {
    throw;
  } catch (const vcpost::Error& e) {
    throw error_from(e, program_file);
  } catch (const std::exception& e) {
    throw error_from_message(e.what());
  }
}

}  // namespace vcpost::api
