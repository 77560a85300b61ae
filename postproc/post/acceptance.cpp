#include "postproc/post/acceptance.h"

#include <algorithm>
#include <vector>

#include "postproc/post/section_words.h"

namespace vcpost::post {

bool is_gross_mismatch(const ToolSection& s) {
  const std::uint64_t on_model = s.touching + s.gouging;
  return s.postable && s.gouging >= kGrossMismatchMinGouging &&
         s.touching * 100 < on_model * kGrossMismatchMaxTouchingPercent;
}

Verdict judge_motion(const PostSummary& summary, const std::string& name) {
  if (summary.motion_events == 0) {
    return {Refusal::no_motion,
            "'" + name +
                "': the program has no motion (empty, comments only, or cut short before "
                "its first move): nothing to post"};
  }
  return {};
}

Verdict judge_posted(const PostSummary& summary, const std::string& name) {
  if (Verdict motion = judge_motion(summary, name); !motion.accepted()) return motion;
  if (!summary.sections.empty() &&
      std::none_of(summary.sections.begin(), summary.sections.end(),
                   [](const ToolSection& s) { return s.entry.has_value(); })) {
    return {Refusal::no_tool,
            "--tool: required (the program names no tool vcpost can read: no CL CUTTER/TLDATA, no "
            "CAM tool comment); give --tool ball:D, --tool T<n>=ball:D or --tools FILE.toml"};
  }
  if (summary.samples > 0 && summary.touching + summary.gouging == 0) {
    const std::string hint =
        "check the work offset and units of the program against the model, and --cl-point (tip "
        "or center)";
    std::string message = "the toolpath never touches the model (" +
                          std::to_string(summary.samples) + " points checked)";
    if (summary.lifted == 0) return {Refusal::never_touches, message + ": " + hint};
    // Points above the model within the search distance: how high, and
    // when one offset dominates (stock left on, a smaller tool), why.
    message += ": " + std::to_string(summary.lifted) + " sit above it" +
               (summary.missed > 0 ? ", " + std::to_string(summary.missed) +
                                         " miss it entirely (no contact within "
                                         "the search distance)"
                                   : std::string());
    bool offset = false;
    for (const ToolSection& s : summary.sections) {
      if (s.lift.points == 0) continue;
      const std::string label =
          summary.sections.size() > 1 ? section_name(s) + ": " : std::string();
      message += "; " + label + depth_words(s.lift, "lift height");
      if (s.offset && s.offset->offset_mm > 0 && s.entry) {
        message += "; " + label + lift_words(*s.offset, s.entry->diameter / 2);
        offset = true;
      }
    }
    if (!offset) message += "; no one offset dominates: " + hint;
    return {Refusal::never_touches, message};
  }
  // A section whose points on the model mostly gouge it: not a few gouges
  // to warn about, the program and the model disagree (another tool
  // diameter, units, work offset or --cl-point). Points in the air (lifted
  // or far from the model) do not count either way: a program with many
  // air moves is judged by its points on the model.
  std::vector<const ToolSection*> gross;
  for (const ToolSection& s : summary.sections) {
    if (is_gross_mismatch(s)) gross.push_back(&s);
  }
  if (gross.empty()) return {};
  std::uint64_t touching = 0, gouging = 0, points = 0;
  for (const ToolSection* s : gross) {
    touching += s->touching;
    gouging += s->gouging;
    points += s->points;
  }
  // The error gives the sections' own diagnosis, worded as the end-of-run
  // lines word it.
  std::string message = "the toolpath gouges the model at " + std::to_string(gouging) + " of " +
                        std::to_string(points) + " points and touches it at only " +
                        std::to_string(touching) + ": the program does not match the model";
  bool offset = false;
  for (const ToolSection* s : gross) {
    const std::string label = summary.sections.size() > 1 ? section_name(*s) + ": " : std::string();
    if (s->gouge.points > 0) message += "; " + label + depth_words(s->gouge, "gouge depth");
    if (s->lift.points > 0) message += "; " + label + depth_words(s->lift, "lift height");
    if (s->offset) message += "; " + label + offset_words(*s->offset);
    offset = offset || s->offset.has_value();
  }
  if (!offset) {
    message +=
        "; no one offset dominates (depths that vary with the surface's slope: a shifted "
        "work offset, other units or another tool diameter)";
  }
  return {Refusal::gross_mismatch, message};
}

}  // namespace vcpost::post
