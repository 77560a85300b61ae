#include "postproc/post/program_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <stdexcept>
#include <variant>

#include "postproc/output/event_writer.h"
#include "postproc/post/klartext_patch.h"

namespace vcpost::post {
namespace {

// The number written for S or F.
std::string format_word(double value, double step, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, on_grid(value, step));
  return buffer;
}

int decimals_of(double step) {
  int decimals = 0;
  while (decimals < 6 && std::abs(step * std::pow(10.0, decimals) -
                                  std::round(step * std::pow(10.0, decimals))) > 1e-9) {
    ++decimals;
  }
  return decimals;
}

}  // namespace

double on_grid(double value, double step) { return std::floor(value / step + 1e-9) * step; }

ProgramWriter::ProgramWriter(std::string_view text, ProgramKind kind,
                             const machines::MachineProfile& profile, bool adjust_feed,
                             std::function<void(std::string_view)> sink,
                             std::function<void(std::uint64_t)> consumed,
                             std::function<bool(std::uint32_t)> keeps)
    : text_(text),
      kind_(kind),
      adjust_feed_(adjust_feed),
      s_step_(profile.spindle().s_resolution_rpm),
      f_step_(std::pow(10.0, -profile.output().feed_decimals)),
      s_decimals_(decimals_of(profile.spindle().s_resolution_rpm)),
      f_decimals_(profile.output().feed_decimals),
      speed_output_(profile.output().speed_output),
      sink_(std::move(sink)),
      consumed_(std::move(consumed)),
      keeps_(std::move(keeps)) {
  if (kind_ == ProgramKind::cldata) {
    cl_writer_ = output::make_event_writer(cl_buffer_, profile);
  } else if (kind_ == ProgramKind::heidenhain) {
    klartext_ = std::make_unique<KlartextPatcher>(text_);
  }
}

ProgramWriter::~ProgramWriter() = default;

std::uint64_t ProgramWriter::s_words(std::uint32_t section) const {
  return section < words_by_section_.size() ? words_by_section_[section].first : 0;
}

std::uint64_t ProgramWriter::f_words(std::uint32_t section) const {
  return section < words_by_section_.size() ? words_by_section_[section].second : 0;
}

void ProgramWriter::add(const Chunk& chunk) {
  // Internal invariant, not the user's input: the post job hands chunks in
  // block order; logic_error marks a bug (exit 3, "internal error").
  if (first_pending_ + pending_.size() != chunk.first_block)
    throw std::logic_error("ProgramWriter: chunks out of order");
  if (chunk.repeat_from) hold_from_ = std::min(hold_from_, *chunk.repeat_from);
  pending_.insert(pending_.end(), chunk.blocks.begin(), chunk.blocks.end());
  events_.insert(events_.end(), chunk.events.begin(), chunk.events.end());
}

const BlockInfo& ProgramWriter::block(std::size_t index) const {
  return pending_.at(index - first_pending_);
}

void ProgramWriter::on_final(const plan::BlockPlan& plan,
                             const std::optional<plan::BlockFeed>& feed) {
  // Internal invariant, not the user's input: the planner finalises only
  // blocks it was given (logic_error: a bug).
  if (plan.block < first_pending_ || plan.block >= first_pending_ + pending_.size())
    throw std::logic_error("ProgramWriter: a final block that is not held");
  const Planned planned{&plan, feed ? &*feed : nullptr};
  while (first_pending_ < plan.block) resolve_front({}, planned);
  resolve_front(planned, planned);
}

void ProgramWriter::flush() {
  if (kind_ != ProgramKind::cldata) {
    if (!pending_.empty()) write_text_until(pending_.front().offset);
  } else {
    flush_cl();
  }
}

void ProgramWriter::finish() {
  while (!pending_.empty()) resolve_front({}, {});
  if (kind_ != ProgramKind::cldata) {
    if (hold_from_ != UINT64_MAX) merge_repeated_patches();
    hold_from_ = UINT64_MAX;
    write_text_until(text_.size());
  } else {
    cl_writer_->finish();
    flush_cl();
  }
}

std::optional<double> ProgramWriter::coupled_feed(const BlockInfo& block, const Planned& own,
                                                  const Planned& next) {
  if (!adjust_feed_ || (own.plan && own.plan->bound == plan::Bound::rapid)) return std::nullopt;
  std::optional<double> f;
  if (own.feed && own.feed->f_word) {
    f = own.feed->f_mm_per_min;
  } else if (block.has_f && next.feed && next.plan->bound != plan::Bound::off &&
             next.plan->bound != plan::Bound::rapid) {
    f = next.feed->f_mm_per_min;
  }
  // A TNC block takes a coupled F only in its own F word with a number.
  if (f && klartext_ && !klartext_->takes_f(block.offset)) return std::nullopt;
  return f;
}

void ProgramWriter::resolve_front(Planned own, Planned next) {
  const BlockInfo block = pending_.front();
  const std::size_t index = first_pending_;
  // The next planned block's S and F carry back only within the section:
  // another section's plan is not this one's.
  if (next.plan && pending_[next.plan->block - first_pending_].section != block.section) next = {};
  const bool keep = keeps_ && keeps_(block.section);
  const bool moves = own.plan != nullptr;
  if (keep) own = next = {};
  pending_.pop_front();
  ++first_pending_;

  // S (F) in effect from this block on, when the plan changes it here: the
  // block's own S word if planned (and not just set to that value before
  // the move), else the next planned block's S for a block that already
  // carries an S word of the program.
  std::optional<double> s;
  if (own.plan && own.plan->s_word) {
    if (block.has_s || on_grid(own.plan->planned_rpm, s_step_) != s_before_motion_)
      s = own.plan->planned_rpm;
  } else if (block.has_s && block.program_s > 0 && next.plan &&
             next.plan->bound != plan::Bound::off) {
    s = next.plan->planned_rpm;
  }
  if (!moves && (s || block.has_s)) {
    s_before_motion_ = on_grid(s ? *s : block.program_s, s_step_);
  } else if (moves) {
    s_before_motion_ = kNoS;
  }
  const std::optional<double> f = coupled_feed(block, own, next);
  if (words_by_section_.size() <= block.section) words_by_section_.resize(block.section + 1);
  auto& [section_s, section_f] = words_by_section_[block.section];
  if (kind_ != ProgramKind::cldata) {
    if (s) {
      s_in_effect_ = on_grid(*s, s_step_);
    } else if (block.has_s) {
      s_in_effect_ = block.program_s;
    }
    if (f) {
      f_in_effect_ = on_grid(*f, f_step_);
    } else if (block.has_f) {
      f_in_effect_ = block.program_f;
    }
    if (block.offset >= hold_from_) {
      HeldLine& line = held_lines_[block.offset];
      line.s = std::fmin(line.s, s_in_effect_);  // fmin: NaN (none yet) counts for nothing
      line.f = std::fmin(line.f, f_in_effect_);
      ++line.runs;
    }
    // With a speed output every speed of the program goes there, also one
    // the plan keeps: the S word alone no longer sets the spindle's speed.
    if (s || (speed_output_ && block.has_s && block.program_s > 0)) {
      patches_.push_back(speed_patch(block, s ? *s : block.program_s));
      ++s_words_;
      ++section_s;
    }
    if (f) {
      patches_.push_back({block.offset, 'F', format_word(*f, f_step_, f_decimals_)});
      ++f_words_;
      ++section_f;
    }
    return;
  }
  // CL: the planned S (F) before the motion of a block that changes it (a
  // new word), or in the block's own S record.
  while (!events_.empty() && events_.front().second <= index) {
    program::Event& event = events_.front().first;
    if (events_.front().second == index) {
      if (program::is_motion(event)) {
        if (s && !block.has_s) {
          cl_writer_->write(program::SetSpindleSpeed{on_grid(*s, s_step_), {}});
          ++s_words_;
          ++section_s;
        }
        if (f && !block.has_f) {
          cl_writer_->write(program::SetFeedRate{
              on_grid(*f, f_step_), program::FeedMode::per_minute, {}, std::nullopt});
          ++f_words_;
          ++section_f;
        }
      } else if (auto* speed = std::get_if<program::SetSpindleSpeed>(&event)) {
        if (s) speed->rpm = on_grid(*s, s_step_);
      }
    }
    cl_writer_->write(event);
    events_.pop_front();
  }
}

gcode::WordPatch ProgramWriter::speed_patch(const BlockInfo& block, double rpm) const {
  gcode::WordPatch patch{block.offset, 'S', format_word(rpm, s_step_, s_decimals_)};
  // S0 stays the S word: it stops the spindle.
  if (!speed_output_ || on_grid(rpm, s_step_) <= 0) return patch;
  patch.form = block.spindle_turns ? gcode::SpeedForm::synced : gcode::SpeedForm::start;
  patch.output = *speed_output_;
  return patch;
}

void ProgramWriter::write_text_until(std::uint64_t offset) {
  offset = std::min(offset, hold_from_);
  if (offset <= written_) return;
  // Patches of held lines (at or after hold_from_) stay for later.
  const auto held = std::stable_partition(
      patches_.begin(), patches_.end(),
      [offset](const gcode::WordPatch& patch) { return patch.block_offset < offset; });
  std::vector<gcode::WordPatch> now(std::make_move_iterator(patches_.begin()),
                                    std::make_move_iterator(held));
  patches_.erase(patches_.begin(), held);
  if (klartext_) {
    if (sink_) klartext_->write(written_, offset, now, sink_);
  } else {
    for (auto& patch : now) patch.block_offset -= written_;
    if (sink_) gcode::write_patched(text_.substr(written_, offset - written_), now, sink_);
  }
  written_ = offset;
  if (consumed_) consumed_(written_);
}

void ProgramWriter::merge_repeated_patches() {
  // In program order, one patch per line and letter. A held line's word
  // gets the lowest S (F) in effect at any of its runs: a run that set it
  // there, and also a run that carried a lower one from a line before (its
  // word now holds for that run too, up to the next word).
  std::stable_sort(patches_.begin(), patches_.end(),
                   [](const gcode::WordPatch& a, const gcode::WordPatch& b) {
                     return a.block_offset != b.block_offset ? a.block_offset < b.block_offset
                                                             : a.letter < b.letter;
                   });
  std::vector<gcode::WordPatch> merged;
  for (auto& patch : patches_) {
    if (!merged.empty() && merged.back().block_offset == patch.block_offset &&
        merged.back().letter == patch.letter) {
      (patch.letter == 'S' ? s_words_ : f_words_) -= 1;
      continue;
    }
    merged.push_back(std::move(patch));
  }
  std::uint64_t last_repeated = UINT64_MAX;
  for (auto& patch : merged) {
    const auto line = held_lines_.find(patch.block_offset);
    if (line == held_lines_.end()) continue;
    const bool s = patch.letter == 'S';
    const double lowest = s ? line->second.s : line->second.f;
    if (!std::isnan(lowest)) {
      std::string value =
          s ? format_word(lowest, s_step_, s_decimals_) : format_word(lowest, f_step_, f_decimals_);
      if (std::strtod(value.c_str(), nullptr) < std::strtod(patch.value.c_str(), nullptr))
        patch.value = std::move(value);
    }
    if (line->second.runs > 1 && last_repeated != patch.block_offset) ++repeated_lines_;
    last_repeated = patch.block_offset;
  }
  patches_ = std::move(merged);
  held_lines_.clear();
}

void ProgramWriter::flush_cl() {
  const std::string chunk = cl_buffer_.str();
  if (!chunk.empty() && sink_) sink_(chunk);
  cl_buffer_.str({});
}

}  // namespace vcpost::post
