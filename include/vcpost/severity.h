// How grave a diagnostic is: the one Severity of vcpost, shared by the
// internal error table (core/error.h) and the public vcpost::api::Error.
#pragma once

namespace vcpost {

enum class Severity { error, warning };

}  // namespace vcpost
