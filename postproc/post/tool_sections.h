// The sections of a program, one per tool change, and which of them the
// post job rewrites: by default every section whose tool is a shape the job
// posts (a ball-end mill) and whose path touches the model; `--post-tools`
// chooses explicitly. Every other section keeps its S and F as written.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "postproc/post/tallies.h"
#include "postproc/tools/tool_table.h"

namespace vcpost::post {

// How far the tool sits from the model where it does not touch: the
// signed distance of the ball from the surface (distance_error of
// geometry::BallContact) over the points that lift (> 0) or gouge (< 0).
struct DepthStatistics {
  std::uint64_t points = 0;
  double min = 0, median = 0, max = 0;  // mm, of |distance| (depths), empty when points = 0
};

// A toolpath consistently off the model: most of a section's points at one
// offset from the surface.
struct OffsetDiagnosis {
  double offset_mm = 0;  // signed: > 0 above the surface, < 0 into it
  double share = 0;      // of the section's points near the model within +-0.02 mm of it
  std::string causes;    // the likely causes, in words
  // The allowance option that would post the section as it is, e.g.
  // "--stock=-1.245 (or --stock T1=-1.245)"; empty where the offset is the
  // tool radius (the CL point, not stock).
  std::string option;
};

// One section of the program: from a tool change (or the start) to the next;
// its points by contact state are the ContactCounts it derives from.
struct ToolSection : ContactCounts {
  std::uint32_t index = 0;  // 0 before the first tool change, then one per tool change
  std::optional<int> tool;  // T number; empty before any tool change
  std::optional<tools::ToolEntry> entry;  // what decided the tool; empty: nothing names it
  std::uint32_t first_line = 0;           // NC line (CL record) of its first motion
  bool postable = false;                  // a shape the job posts, chosen, with a vc: evaluated
  bool posted = false;                    // postable and its path touches the model: S rewritten
  std::string reason;                     // why it is posted or kept, in words
  double vc_nominal = 0;                  // m/min (posted sections)
  geometry::Allowance stock;              // the allowance its contact is with (--stock)

  // Filled as the job runs.
  double start_s = 0, end_s = 0;           // program time of its first and last motion
  std::uint64_t points = 0;                // path samples (evaluated when postable)
  std::uint64_t s_words = 0, f_words = 0;  // written in its blocks
  std::optional<VcStatistics> before, after;
  DepthStatistics gouge, lift;
  std::optional<OffsetDiagnosis> offset;
};

// The shapes the job posts: ball and bull-nose end mills (the pipeline
// models both; a flat end mill's face is usually not a finishing edge and
// its section keeps its speed).
bool posts_shape(tools::ToolShape shape);

// Decides a section at its first motion from the tool the sources give
// (`tool`: null when nothing names it). Throws PostError for a posted tool
// whose diameter is not above --ap.
ToolSection decide_section(std::uint32_t index, std::optional<int> number, std::uint32_t first_line,
                           const tools::ToolEntry* tool, const tools::ToolChoices& choices,
                           double ap_mm);

// The tool numbers the command line names (--post-tools, --vc T2=..,
// --tool T8=..; not a tools file, a shop's whole table) that no section of
// the program selects, each as a warning in words: a typo or the wrong
// program, which otherwise only shows as a tool posted at another speed or
// not at all.
std::vector<std::string> unused_tool_choices(const tools::ToolChoices& choices,
                                             const std::vector<ToolSection>& sections);

}  // namespace vcpost::post
