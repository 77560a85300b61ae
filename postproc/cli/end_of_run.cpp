// The end-of-run lines of `vcpost post` and `vcpost report` on standard
// error, the warnings among them, and the --summary-json file.
#include "postproc/cli/end_of_run.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

#include "postproc/cli/atomic_file.h"
#include "postproc/cli/job_reports.h"
#include "postproc/cli/log.h"
#include "postproc/post/section_words.h"
#include "postproc/report/report.h"

namespace vcpost::cli {
namespace {

// The nominal vc of the posted sections: one number, or their range.
std::string vc_words(const post::PostSummary& summary) {
  double low = HUGE_VAL, high = -HUGE_VAL;
  for (const post::ToolSection& s : summary.sections) {
    if (!s.posted) continue;
    low = std::min(low, s.vc_nominal);
    high = std::max(high, s.vc_nominal);
  }
  std::ostringstream out;
  out << low;
  if (high > low) out << "-" << high;
  return out.str();
}

// The share of the posted cutting time whose S a spindle limit decided,
// and of the coupled blocks whose F a feed limit decided: all but nothing
// left to the model means --vc or --fz is beyond the machine (W2031, W2032).
constexpr double kAllClamped = 0.99;

double clamped_speed_share(const post::PostSummary& summary) {
  double cutting = 0;
  for (const auto& s : summary.s_placement.sections) cutting += s.cutting_time_s;
  return cutting > 0 ? (summary.time_clamped_max_s + summary.time_clamped_min_s) / cutting : 0;
}

double clamped_feed_share(const post::PostSummary& summary) {
  return summary.coupled_feed_blocks > 0 ? static_cast<double>(summary.clamped_feed_blocks) /
                                               static_cast<double>(summary.coupled_feed_blocks)
                                         : 0;
}

// One line per section, when there is more than one or one is kept.
void print_sections(const post::PostSummary& summary) {
  const bool all_posted = std::all_of(summary.sections.begin(), summary.sections.end(),
                                      [](const post::ToolSection& s) { return s.posted; });
  if (summary.sections.size() <= 1 && all_posted) return;
  for (const post::ToolSection& s : summary.sections) {
    std::ostringstream line;  // numbers as the stream writes them (vc: 6 digits)
    line << "  line " << s.first_line << ": " << post::section_name(s) << ": ";
    if (s.posted) {
      line << "posted at vc " << s.vc_nominal << " m/min, " << s.points << " points, " << s.s_words
           << " S words";
      if (s.before && s.after) {
        line << ", within +-10 %: "
             << static_cast<int>(std::round(s.before->within_10_percent * 100)) << " % before, "
             << static_cast<int>(std::round(s.after->within_10_percent * 100)) << " % after";
      }
    } else {
      line << "kept, " << s.reason << " (" << s.points << " points)";
    }
    log().info("{}", line.str());
  }
}

// The allowance each evaluated section's contact was taken with, when any.
void print_allowances(const post::PostSummary& summary) {
  for (const post::ToolSection& s : summary.sections) {
    if (!s.postable || s.stock.is_zero()) continue;
    std::ostringstream line;
    line << "  " << post::section_name(s) << ": contact with the model offset by "
         << s.stock.radial;
    if (!s.stock.is_uniform()) line << " mm radially, " << s.stock.axial << " axially";
    line << " mm (--stock)";
    log().info("{}", line.str());
  }
}

// The in-process stock: what it was, what ap it gave; its warnings.
void print_stock(const post::PostSummary& summary) {
  if (!summary.stock) return;
  for (const std::string& line : post::stock_lines(*summary.stock)) log().info("  {}", line);
  for (const std::string& warning : summary.stock->warnings) log().warn("{}", warning);
}

// Gouge and lift depths of the evaluated sections, and the diagnosis of a
// path consistently off the model.
void print_depths(const post::PostSummary& summary) {
  for (const post::ToolSection& s : summary.sections) {
    const std::string name =
        summary.sections.size() > 1 ? post::section_name(s) + ": " : std::string();
    for (const auto& [depth, what] :
         {std::pair{&s.gouge, "gouge depth"}, std::pair{&s.lift, "lift height"}}) {
      if (depth->points > 0) log().info("  {}{}", name, post::depth_words(*depth, what));
    }
    if (s.offset) log().warn("{}{}", name, post::offset_words(*s.offset));
  }
}

}  // namespace

bool has_warnings(const post::PostSummary& summary) {
  // Without a model the points kept (no normal) are counted in their own line.
  const bool off_model = !summary.path_normals && summary.lifted + summary.missed > 0;
  return summary.gouging > 0 || off_model || summary.missing_end ||
         !summary.unread_after_end.empty() || summary.stopped_spindle_cuts > 0 ||
         clamped_speed_share(summary) >= kAllClamped || clamped_feed_share(summary) >= kAllClamped;
}

void print_warnings(const post::PostSummary& summary, const std::string& name) {
  if (summary.stopped_spindle_cuts > 0) {
    log().warn(
        "{}:{}: {}: {} points cut the model with the spindle stopped (S0, M5 or SPINDL/OFF "
        "before them): the control would cut with a standing tool; vcpost keeps their S",
        name, summary.first_stopped_spindle_line, to_string(Code::W2030),
        summary.stopped_spindle_cuts);
  }
  if (clamped_speed_share(summary) >= kAllClamped) {
    log().warn(
        "{}: the spindle's {} speed decides S on {:.0f} % of the cutting time: vc {} m/min is "
        "beyond this machine with this tool (check --vc, the tool and --machine)",
        to_string(Code::W2031),
        summary.time_clamped_max_s >= summary.time_clamped_min_s ? "highest" : "lowest",
        100 * clamped_speed_share(summary), vc_words(summary));
  }
  if (clamped_feed_share(summary) >= kAllClamped) {
    log().warn(
        "{}: the machine's feed limit (f_min or f_max) decides F on {:.0f} % of the coupled "
        "blocks: --fz is beyond this machine (check --fz, the teeth and --machine)",
        to_string(Code::W2032), 100 * clamped_feed_share(summary));
  }
  if (summary.missing_end)
    log().warn("the program ends without M2, M30 or a closing '%': is the file complete?");
  // The reader's own diagnostic, with its file position and code.
  if (!summary.unread_after_end.empty()) std::cerr << summary.unread_after_end << '\n';
  if (summary.gouging > 0) log().warn("{} points gouge the model", summary.gouging);
  if (!summary.path_normals && summary.lifted + summary.missed > 0) {
    log().warn("{} cutting points do not touch the model (their blocks keep the program's S)",
               summary.lifted + summary.missed);
  }
}

void finish_job(const PostArguments& args, const JobRun& run) {
  const post::PostSummary& summary = run.summary;
  std::vector<std::string> notes = run.notes;
  if (!args.summary_json.empty()) {
    const std::string json =
        report::post_summary_json(summary_inputs(args, run), run.tool.has_value(), summary,
                                  run.run_time_s)
            .dump(2) +
        "\n";
    if (args.summary_json == "-") {
      std::cerr << json;
    } else {
      AtomicFile out(args.summary_json);
      out.write(json);
      out.commit();
      note_links(out, args.summary_json, notes);
    }
  }
  std::ostringstream totals;  // vc as the stream writes it
  totals << summary.samples << " points, " << summary.s_words << " S words";
  if (args.adjust_feed) totals << ", " << summary.f_words << " F words";
  if (summary.before && summary.after) {
    totals << "; cutting time within +-10 % of vc " << vc_words(summary)
           << " m/min: " << static_cast<int>(std::round(summary.before->within_10_percent * 100))
           << " % before, " << static_cast<int>(std::round(summary.after->within_10_percent * 100))
           << " % after";
  }
  log().info("{}", totals.str());
  print_sections(summary);
  print_allowances(summary);
  print_stock(summary);
  for (const auto& path : args.reports) {
    if (path != "-") log().info("report written to {}", path);
  }
  for (const auto& note : notes) {
    constexpr std::string_view kWarning = "warning: ";
    if (note.starts_with(kWarning)) {
      log().warn("{}", note.substr(kWarning.size()));
    } else {
      log().info("{}", note);
    }
  }
  if (summary.repeated_lines > 0) {
    log().info(
        "{} lines run more than once (subroutines, loops): each has the lowest S (F) of its runs",
        summary.repeated_lines);
  }
  print_depths(summary);
  for (const std::string& note : summary.tool_notes) log().info("note: {}", note);
  if (summary.path_normals) {
    const pipeline::PathNormalCounts& n = *summary.path_normals;
    log().info(
        "no --model: each point's normal from the toolpath: {} two-sided, {} one-sided, {} "
        "without one (no pass near enough: no S of their own, a pass with none keeps the "
        "program's); no gouge check, no cusp map",
        n.two_sided, n.one_sided, n.kept);
  } else if (args.model.empty()) {
    log().info("no --model: the CL data is translated for {} with its own speeds",
               run.profile.name());
  } else if (!summary.sections.empty() &&
             std::none_of(summary.sections.begin(), summary.sections.end(),
                          [](const post::ToolSection& s) { return s.posted; })) {
    log().warn(
        "no section is posted (each section's reason is above): the program keeps its own "
        "speeds");
  }
  print_warnings(summary, program_name(args));
}

}  // namespace vcpost::cli
