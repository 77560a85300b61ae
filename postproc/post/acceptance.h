// Whether a finished post is worth writing: the rules that refuse a program
// vcpost cannot have posted sensibly (no motion, no tool it can read, a
// toolpath that never touches the model, or one that mostly gouges it). A
// verdict, not an exit: the command line maps each refusal to its code.
#pragma once

#include <cstdint>
#include <string>

#include "postproc/post/post_job.h"

namespace vcpost::post {

enum class Refusal {
  none,            // accepted
  no_motion,       // the program has no motion
  no_tool,         // no section has a tool vcpost can read
  never_touches,   // no point of the toolpath touches the model
  gross_mismatch,  // a section's points on the model mostly gouge it
};

struct Verdict {
  Refusal refusal = Refusal::none;
  std::string message;  // why, naming the program, the sections' depths and a hint
  bool accepted() const { return refusal == Refusal::none; }
};

// A gross program/model mismatch: an evaluated section with at least
// kGrossMismatchMinGouging gouging points of which fewer than
// kGrossMismatchMaxTouchingPercent % of its points on the model (touching
// or gouging) touch it. Points in the air (lifted, or too far from the
// model) count neither way.
inline constexpr std::uint64_t kGrossMismatchMinGouging = 10;
inline constexpr std::uint64_t kGrossMismatchMaxTouchingPercent = 10;
bool is_gross_mismatch(const ToolSection& section);

// Only the first rule: the program has a motion (CL data translated
// without a model is judged by it alone). `name`: the program in messages.
Verdict judge_motion(const PostSummary& summary, const std::string& name);
// Every rule, in the order above.
Verdict judge_posted(const PostSummary& summary, const std::string& name);

}  // namespace vcpost::post
