// How the facade turns the internals' failures into the one public
// vcpost::api::Error: every call of <vcpost/...> runs inside guarded().
#pragma once

#include <exception>
#include <string>
#include <utility>

#include "core/error.h"
#include "vcpost/error.h"

namespace vcpost::api {

// The Error for one of vcpost's own: its code, hint, severity and place as
// it carries them (where(); the text is never read for a place);
// `program_file` names the file of a place that has a line but no file
// (the readers' errors: the text they read has no name).
Error error_from(const vcpost::Error& error, const std::string& program_file);

// Runs `work`; anything it throws but an Error leaves as an Error (any
// other exception with its text as the message, no code and no place).
template <class Work>
auto guarded(Work&& work, const std::string& program_file = {}) -> decltype(work()) {
  try {
    return std::forward<Work>(work)();
  } catch (const Error&) {
    throw;
  } catch (const vcpost::Error& e) {
    throw error_from(e, program_file);
  } catch (const std::exception& e) {
    throw Error(e.what(), {}, e.what());
  }
}

}  // namespace vcpost::api
