// The tool sections as the post job's last stage follows them: whether
// each one's S words are rewritten (pending until its first point touches
// the model), its entry in the summary, its vc tallies and offset
// histogram.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "geometry/model.h"
#include "postproc/post/offset_diagnosis.h"
#include "postproc/post/post_job.h"
#include "postproc/post/program_writer.h"
#include "postproc/post/tallies.h"

namespace vcpost::post {

// Whether a section's S words are rewritten. A postable section is pending
// until its first point touches the model (posted) or it ends without one
// (kept: in the air); its final blocks wait meanwhile, so a section in the
// air keeps its S byte for byte.
enum class SectionState : std::uint8_t { kept, pending, posted };

struct SectionLedger {
  std::size_t summary_index = 0;  // in PostSummary::sections
  SectionState state = SectionState::kept;
  VcTally before, after;
  std::optional<OffsetHistogram> offsets;  // postable sections
  bool timed = false;                      // start_s set
  bool summarised = false;                 // a ToolSection exists
};

class SectionLedgers {
 public:
  // Sections go into `summary`; contact_tolerance_mm sizes the offset histograms.
  SectionLedgers(PostSummary& summary, double contact_tolerance_mm)
      : summary_(summary), tolerance_(contact_tolerance_mm) {}

  // A section starts (the reader announces it before its first slot).
  void open(ToolSection section);

  // kept for a section never opened.
  SectionState state(std::uint32_t section) const {
    return section < ledgers_.size() ? ledgers_[section].state : SectionState::kept;
  }
  // Null for a section never opened (no ledger: nothing to tally).
  SectionLedger* ledger(std::uint32_t section) {
    return section < ledgers_.size() ? &ledgers_[section] : nullptr;
  }

  // Its nominal vc (m/min; 0 unless postable) and its tool's teeth as its
  // entry (tools file) gives them (0: --teeth or the profile's).
  double nominal_vc(std::uint32_t section) const {
    const ToolSection* s = summary_of(section);
    return s ? s->vc_nominal : 0.0;
  }
  int teeth(std::uint32_t section) const {
    const ToolSection* s = summary_of(section);
    return s && s->entry && s->entry->teeth ? *s->entry->teeth : 0;
  }
  // Its tool's shape and size, where its entry gives them.
  std::optional<geometry::Tool> tool(std::uint32_t section) const {
    const ToolSection* s = summary_of(section);
    return s && s->entry ? s->entry->geometry() : std::nullopt;
  }

  // A pending section is decided in the air: kept, for `reason`.
  void keep(std::uint32_t section, const std::string& reason);

  // A slot of `section` at program time `time_s`: the section's start and
  // end. Inline, as count_sample: both run once a path sample.
  void stamp(std::uint32_t section, double time_s) {
    ToolSection* s = summary_of(section);
    if (!s) return;
    SectionLedger& l = ledgers_[section];
    if (!l.timed) s->start_s = time_s;
    l.timed = true;
    s->end_s = time_s;
  }
  // A kept slot (a section not evaluated) counts as one of its points.
  void count_kept(std::uint32_t section);
  // An evaluated sample: its contact into the counts and the offsets, and
  // the section posted from its first touching point (one that only
  // gouges, a model in other units or another tool, has no vc to keep).
  void count_sample(std::uint32_t section, geometry::BallStatus status, double distance_error) {
    SectionLedger& ledger = ledgers_[section];
    ToolSection& s = summary_.sections[ledger.summary_index];
    ++s.points;
    summary_.count_contact(status);
    s.count_contact(status);
    if (status != geometry::BallStatus::missed && ledger.offsets)
      ledger.offsets->add(distance_error);
    if (ledger.state == SectionState::pending && status == geometry::BallStatus::touching)
      ledger.state = SectionState::posted;
  }

  // Every section's results into its summary entry.
  void finish(const ProgramWriter& writer);

 private:
  ToolSection* summary_of(std::uint32_t section) const {
    if (section >= ledgers_.size() || !ledgers_[section].summarised) return nullptr;
    return &summary_.sections[ledgers_[section].summary_index];
  }

  PostSummary& summary_;
  double tolerance_;
  std::vector<SectionLedger> ledgers_;  // by section index
};

}  // namespace vcpost::post
