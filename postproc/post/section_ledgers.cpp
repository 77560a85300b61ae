#include "postproc/post/section_ledgers.h"

namespace vcpost::post {

void SectionLedgers::open(ToolSection section) {
  const std::uint32_t index = section.index;
  if (ledgers_.size() <= index) ledgers_.resize(index + 1);
  SectionLedger& l = ledgers_[index];
  l.summary_index = summary_.sections.size();
  l.state = section.postable ? SectionState::pending : SectionState::kept;
  if (section.postable && section.entry)
    l.offsets.emplace(tolerance_, section.entry->diameter / 2, section.stock, section.tool);
  l.summarised = true;
  summary_.sections.push_back(std::move(section));
}

void SectionLedgers::keep(std::uint32_t section, const std::string& reason) {
  if (section >= ledgers_.size()) return;
  ledgers_[section].state = SectionState::kept;
  if (ToolSection* s = summary_of(section)) s->reason = reason;
}

void SectionLedgers::count_kept(std::uint32_t section) {
  if (ToolSection* s = summary_of(section)) ++s->points;
}

void SectionLedgers::finish(const ProgramWriter& writer) {
  for (std::uint32_t i = 0; i < ledgers_.size(); ++i) {
    SectionLedger& l = ledgers_[i];
    ToolSection* s = summary_of(i);
    if (!s) continue;
    s->posted = l.state == SectionState::posted;
    s->before = l.before.statistics();
    s->after = l.after.statistics();
    s->s_words = writer.s_words(i);
    s->f_words = writer.f_words(i);
    if (l.offsets) {
      s->gouge = l.offsets->gouge();
      s->lift = l.offsets->lift();
      s->offset = l.offsets->diagnosis();
    }
  }
}

}  // namespace vcpost::post
