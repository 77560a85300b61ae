#include "postproc/post/path_normal_reader.h"

#include <tbb/parallel_pipeline.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <span>

namespace vcpost::post {

namespace {

// The normal of a sample `t` along a move between its ends' normals; one
// end without a normal (a pass's last move): the other end's.
pipeline::PathNormal normal_between(const pipeline::PathNormal& a, const pipeline::PathNormal& b,
                                    double t) {
  if (a.source == pipeline::NormalSource::kept || b.source == pipeline::NormalSource::kept) {
    const pipeline::PathNormal& found = a.source == pipeline::NormalSource::kept ? b : a;
    if (found.source == pipeline::NormalSource::kept) return {};
    return {found.normal, pipeline::NormalSource::one_sided};
  }
  const Eigen::Vector3d m = (1 - t) * a.normal + t * b.normal;
  if (m.norm() < 0.5) return {};
  return {m.normalized(), std::max(a.source, b.source)};  // the weaker of the two
}

// The earlier pass of a sample `t` along a move: between its ends' (or the
// one end's that has one; ae is measured across the feed, so a point a
// little along it still serves).
pipeline::EarlierPass earlier_between(const pipeline::EarlierPass& a,
                                      const pipeline::EarlierPass& b, double t) {
  if (!a.found || !b.found) return a.found ? a : b;
  const Eigen::Vector3d m = (1 - t) * a.normal + t * b.normal;
  if (m.norm() < 0.5) return {};
  return {(1 - t) * a.point + t * b.point, m.normalized(), true};
}

// The moves' ends of the samples, chunk by chunk in path order, one
// estimator a section (each tool's path lies on its own offset surface),
// each section's normals found as soon as the next one starts.
class EndsBySection {
 public:
  // lines: the program's, a guess at its moves' ends (the room a section
  // takes, as many as are left to read: one allocation, touched only as far
  // as it is filled).
  explicit EndsBySection(std::size_t lines) : lines_(lines) {}

  void take(const Chunk& chunk) {
    for (const ToolSection& s : chunk.sections) {
      if (diameters_.size() <= s.index) diameters_.resize(s.index + 1, 0.0);
      if (s.postable) diameters_[s.index] = s.entry->geometry()->diameter;
    }
    for (const Slot& slot : chunk.slots) {
      if (slot.kind != SlotKind::sample) {
        after_rapid_ = after_rapid_ || slot.kind == SlotKind::rapid;
        continue;
      }
      bounds_.extend(slot.sample.point);
      const bool new_section = slot.section != section_;
      const bool inside = slot.sample.fraction > 0 && slot.sample.fraction < 1;
      if (inside && !new_section && !slot.break_pass && !after_rapid_ && ends_ > 0) {
        places_.push_back({ends_ - 1, slot.sample.fraction});
        continue;
      }
      if (new_section) start_section(slot.section);
      open_->add(slot.sample.point, new_section || slot.break_pass || after_rapid_);
      after_rapid_ = false;
      places_.push_back({ends_++, 1});
    }
    if (open_) open_->track();
    read_before_ = chunk.read_fraction;
  }

  // All read: the normals and earlier passes at the samples.
  PathNormalsAhead finish() {
    finish_section();
    if (places_.size() == ends_) {  // every sample a move's end
      return {std::move(at_ends_), std::move(earlier_at_ends_), bounds_};
    }
    PathNormalsAhead ahead{std::vector<pipeline::PathNormal>(places_.size()),
                           std::vector<pipeline::EarlierPass>(places_.size()), bounds_};
    for (std::size_t i = 0; i < places_.size(); ++i) {
      const Place& p = places_[i];
      if (p.fraction >= 1 || p.end + 1 >= at_ends_.size()) {
        ahead.normals[i] = at_ends_[p.end];
        ahead.earlier[i] = earlier_at_ends_[p.end];
        continue;
      }
      ahead.normals[i] = normal_between(at_ends_[p.end], at_ends_[p.end + 1], p.fraction);
      ahead.earlier[i] =
          earlier_between(earlier_at_ends_[p.end], earlier_at_ends_[p.end + 1], p.fraction);
    }
    return ahead;
  }

 private:
  void start_section(std::uint32_t section) {
    finish_section();
    const double diameter = diameters_.at(section);
    pipeline::PathNormalSettings path_settings;
    path_settings.search_radius = diameter;
    path_settings.min_path_gap = 4 * diameter;  // as the post's own pass tracker
    open_.emplace(path_settings);
    open_->reserve(static_cast<std::size_t>(static_cast<double>(lines_) * (1 - read_before_)));
    section_ = section;
  }

  void finish_section() {
    if (!open_) return;
    std::vector<pipeline::EarlierPass> earlier;
    std::vector<pipeline::PathNormal> found = open_->finish(&earlier);
    open_.reset();
    if (at_ends_.empty()) {  // most programs: one section, no copy
      at_ends_ = std::move(found);
      earlier_at_ends_ = std::move(earlier);
      return;
    }
    at_ends_.insert(at_ends_.end(), found.begin(), found.end());
    earlier_at_ends_.insert(earlier_at_ends_.end(), earlier.begin(), earlier.end());
  }

  // Each sample: the move end it is (fraction 1), or the one before it and
  // how far along the move to the next it lies.
  struct Place {
    std::size_t end = 0;
    double fraction = 1;
  };
  std::vector<Place> places_;
  std::size_t ends_ = 0;
  std::size_t lines_;
  double read_before_ = 0;                             // share of the input read before this chunk
  std::optional<pipeline::PathNormalEstimator> open_;  // the section being read
  // The normals and earlier passes at the ends of the sections read.
  std::vector<pipeline::PathNormal> at_ends_;
  std::vector<pipeline::EarlierPass> earlier_at_ends_;
  std::vector<double> diameters_;  // by section index
  std::optional<std::uint32_t> section_;
  bool after_rapid_ = false;
  Eigen::AlignedBox3d bounds_;
};

}  // namespace

PathNormalsAhead normals_from_path(std::string_view text, const std::string& file_name,
                                   ProgramKind kind, const gcode::Dialect& dialect,
                                   const machines::MachineProfile& profile,
                                   const PostSettings& settings,
                                   const tools::ToolChoices& choices) {
  PathReader reader(text, file_name, kind, dialect, profile, settings.sample_spacing_mm, false,
                    choices, settings.point.ap);
  reader.set_program_loader(settings.program_loader);
  EndsBySection ends(static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1);
  // The reading and the pass tracker side by side: two chunks in flight,
  // one more to fill.
  constexpr std::size_t in_flight = 2;
  std::array<Chunk, in_flight + 1> chunks;
  std::size_t reads = 0;
  tbb::parallel_pipeline(
      in_flight, tbb::make_filter<void, Chunk*>(tbb::filter_mode::serial_in_order,
                                                [&](tbb::flow_control& control) -> Chunk* {
                                                  Chunk* chunk = &chunks[reads++ % chunks.size()];
                                                  if (!reader.read(*chunk, chunk_samples)) {
                                                    control.stop();
                                                    return nullptr;
                                                  }
                                                  return chunk;
                                                }) &
                     tbb::make_filter<Chunk*, void>(tbb::filter_mode::serial_in_order,
                                                    [&](Chunk* chunk) { ends.take(*chunk); }));
  return ends.finish();
}

}  // namespace vcpost::post
