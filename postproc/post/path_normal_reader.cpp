#include "postproc/post/path_normal_reader.h"

#include <algorithm>
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

}  // namespace

PathNormalsAhead normals_from_path(std::string_view text, const std::string& file_name,
                                   ProgramKind kind, const gcode::Dialect& dialect,
                                   const machines::MachineProfile& profile,
                                   const PostSettings& settings,
                                   const tools::ToolChoices& choices) {
  PathReader reader(text, file_name, kind, dialect, profile, settings.sample_spacing_mm, false,
                    choices, settings.point.ap);
  reader.set_program_loader(settings.program_loader);
  std::vector<Eigen::Vector3d> points;  // the moves' ends
  std::vector<std::uint8_t> starts;
  // Each sample: the move end it is (fraction 1), or the one before it and
  // how far along the move to the next it lies.
  struct Place {
    std::size_t end = 0;
    double fraction = 1;
  };
  std::vector<Place> places;
  struct Run {
    std::size_t begin = 0;
    double diameter = 0;
  };
  std::vector<Run> runs;
  std::vector<double> diameters;  // by section index
  std::optional<std::uint32_t> section;
  bool after_rapid = false;
  Eigen::AlignedBox3d bounds;
  Chunk chunk;
  while (reader.read(chunk, chunk_samples)) {
    for (const ToolSection& s : chunk.sections) {
      if (diameters.size() <= s.index) diameters.resize(s.index + 1, 0.0);
      if (s.postable) diameters[s.index] = s.entry->geometry()->diameter;
    }
    for (const Slot& slot : chunk.slots) {
      if (slot.kind != SlotKind::sample) {
        after_rapid = after_rapid || slot.kind == SlotKind::rapid;
        continue;
      }
      bounds.extend(slot.sample.point);
      const bool new_section = slot.section != section;
      const bool inside = slot.sample.fraction > 0 && slot.sample.fraction < 1;
      if (inside && !new_section && !slot.break_pass && !after_rapid && !points.empty()) {
        places.push_back({points.size() - 1, slot.sample.fraction});
        continue;
      }
      if (new_section) {
        runs.push_back({points.size(), diameters.at(slot.section)});
        section = slot.section;
      }
      starts.push_back(new_section || slot.break_pass || after_rapid ? 1 : 0);
      after_rapid = false;
      places.push_back({points.size(), 1});
      points.push_back(slot.sample.point);
    }
  }
  std::vector<pipeline::PathNormal> at_ends;
  std::vector<pipeline::EarlierPass> earlier_at_ends, earlier_found;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const std::size_t begin = runs[r].begin;
    const std::size_t end = r + 1 < runs.size() ? runs[r + 1].begin : points.size();
    pipeline::PathNormalSettings path_settings;
    path_settings.search_radius = runs[r].diameter;
    path_settings.min_path_gap = 4 * runs[r].diameter;  // as the post's own pass tracker
    auto found = pipeline::estimate_path_normals(std::span(points).subspan(begin, end - begin),
                                                 std::span(starts).subspan(begin, end - begin),
                                                 path_settings, &earlier_found);
    if (r == 0) {  // most programs: one section, no copy
      at_ends = std::move(found);
      earlier_at_ends = std::move(earlier_found);
      continue;
    }
    at_ends.insert(at_ends.end(), found.begin(), found.end());
    earlier_at_ends.insert(earlier_at_ends.end(), earlier_found.begin(), earlier_found.end());
  }
  if (places.size() == points.size()) {  // every sample a move's end
    return {std::move(at_ends), std::move(earlier_at_ends), bounds};
  }
  PathNormalsAhead ahead{std::vector<pipeline::PathNormal>(places.size()),
                         std::vector<pipeline::EarlierPass>(places.size()), bounds};
  std::vector<pipeline::PathNormal>& normals = ahead.normals;
  for (std::size_t i = 0; i < places.size(); ++i) {
    const Place& p = places[i];
    if (p.fraction >= 1 || p.end + 1 >= at_ends.size()) {
      normals[i] = at_ends[p.end];
      ahead.earlier[i] = earlier_at_ends[p.end];
      continue;
    }
    normals[i] = normal_between(at_ends[p.end], at_ends[p.end + 1], p.fraction);
    ahead.earlier[i] =
        earlier_between(earlier_at_ends[p.end], earlier_at_ends[p.end + 1], p.fraction);
  }
  return ahead;
}

}  // namespace vcpost::post
