#include "postproc/post/post_job.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <istream>
#include <limits>
#include <sstream>
#include <streambuf>
#include <variant>
#include <vector>

#include "postproc/cldata/cl_reader.h"
#include "postproc/gcode/interpreter.h"
#include "postproc/gcode/writer.h"
#include "postproc/output/mazak_writer.h"
#include "postproc/pipeline/path_sampler.h"
#include "postproc/program/timing.h"

namespace vcpost::post {
namespace {

using program::Event;

// An istream over text held elsewhere, without copying it.
class ViewBuffer : public std::streambuf {
 public:
  explicit ViewBuffer(std::string_view text) {
    char* begin = const_cast<char*>(text.data());  // read only: the get area is never written
    setg(begin, begin, begin + text.size());
  }
};

// Reads the events of either kind of program, one batch at a time.
class EventSource {
 public:
  EventSource(std::string_view text, const std::string& file_name, ProgramKind kind,
              const gcode::Dialect& dialect)
      : kind_(kind), buffer_(text) {
    if (kind == ProgramKind::gcode) {
      gcode_.emplace(text, dialect);
    } else {
      stream_.emplace(&buffer_);
      cl_.emplace(*stream_, file_name);
    }
  }
  bool next(std::vector<Event>& out) {
    if (gcode_) return gcode_->next(out);
    auto event = cl_->next();
    if (!event) return false;
    out.push_back(std::move(*event));
    return true;
  }

 private:
  ProgramKind kind_;
  ViewBuffer buffer_;
  std::optional<std::istream> stream_;
  std::optional<gcode::Interpreter> gcode_;
  std::optional<cldata::ClReader> cl_;
};

gcode::Dialect dialect_of(const machines::MachineProfile& profile) {
  switch (profile.dialect()) {
    case machines::Dialect::fanuc: return gcode::fanuc_dialect();
    case machines::Dialect::mazak: return gcode::mazak_dialect();
    case machines::Dialect::rs274ngc: break;
  }
  return gcode::rs274ngc_dialect();
}

// Numbers the blocks of a program as both passes see them: a G-code block
// is a line (its events share a source offset); in CL data every motion
// starts a block, and what comes before the first motion is block 0.
class BlockCounter {
 public:
  explicit BlockCounter(ProgramKind kind) : kind_(kind) {}
  // The block of `event`, and whether it starts a new one.
  std::pair<std::size_t, bool> on(const Event& event) {
    const program::SourceRef ref = program::source_of(event);
    const bool fresh = kind_ == ProgramKind::gcode ? ref.offset != last_offset_ || !started_
                                                   : program::is_motion(event) || !started_;
    if (fresh && started_) ++block_;
    started_ = true;
    last_offset_ = ref.offset;
    return {block_, fresh};
  }

 private:
  ProgramKind kind_;
  bool started_ = false;
  std::size_t block_ = 0;
  std::uint64_t last_offset_ = 0;
};

// What the job remembers of each block of the program.
struct BlockInfo {
  std::uint64_t offset = 0;   // first byte (G-code) / record (CL)
  bool has_s = false, has_f = false;
  double program_s = 0, program_f = 0;  // in effect on the block
};

// What it remembers of each evaluated sample, for the statistics.
struct SampleInfo {
  float d_ref = NAN;     // mm; NaN where the tool does not cut
  float weight_s = 0;    // cutting time this sample stands for
  std::uint32_t block = 0;
};

// Big enough to mean "no finite limit" to the planner (d_ref = 0).
constexpr double unbounded_rpm = 1e12;

struct Collected {
  std::vector<BlockInfo> blocks;
  std::vector<plan::Sample> timeline;
  std::vector<SampleInfo> samples;
  PostSummary summary;
};

// Sees every evaluated point during collection, with its block and time.
using Observer = std::function<void(const pipeline::PathSample&, const pipeline::PointResult&,
                                    std::size_t block, double time_s, double weight_s)>;

Collected collect(EventSource& source, std::string_view text, ProgramKind kind,
                  const geometry::SurfaceModel& model, const machines::MachineProfile& profile,
                  const PostSettings& settings, const Progress& progress,
                  const Observer& observer = {}) {
  Collected c;
  c.summary.kind = kind;
  program::PathClock clock({profile.feed().rapid_mm_per_min, profile.control().block_time_s});
  pipeline::PathSampler sampler(settings.sample_spacing_mm);
  pipeline::PointEvaluator evaluator(model, settings.point);
  std::vector<Event> events;
  std::vector<pipeline::PathSample> path;
  plan::SpindleState spindle = plan::SpindleState::off;
  program::SpindleDirection direction = program::SpindleDirection::clockwise;
  double program_s = 0, program_f = 0;
  bool tool_change = false;
  std::optional<double> last_target;  // of the last sample evaluated
  bool last_air = true;
  double next_report = 0.01;

  BlockCounter counter(kind);
  auto spindle_state = [&] {
    if (spindle == plan::SpindleState::off || program_s <= 0) return plan::SpindleState::off;
    return direction == program::SpindleDirection::clockwise ? plan::SpindleState::cw
                                                             : plan::SpindleState::ccw;
  };

  while (source.next(events)) {
    for (const Event& event : events) {
      const bool motion = program::is_motion(event);
      const auto [block_index, fresh] = counter.on(event);
      if (fresh) c.blocks.push_back({program::source_of(event).offset, false, false, program_s, program_f});
      BlockInfo& block = c.blocks.back();
      const program::EventTime time = clock.advance(event);
      if (const auto* s = std::get_if<program::SetSpindleSpeed>(&event)) {
        program_s = block.program_s = s->rpm;
        block.has_s = true;
        if (s->rpm <= 0) spindle = plan::SpindleState::off;
      } else if (const auto* on = std::get_if<program::SpindleOn>(&event)) {
        direction = on->direction;
        spindle = plan::SpindleState::cw;  // direction applied in spindle_state()
      } else if (std::holds_alternative<program::SpindleOff>(event)) {
        spindle = plan::SpindleState::off;
      } else if (const auto* f = std::get_if<program::SetFeedRate>(&event)) {
        program_f = block.program_f = f->rate;
        block.has_f = true;
      } else if (std::holds_alternative<program::ChangeTool>(event)) {
        tool_change = true;
        evaluator.break_pass();
      }
      if (!motion) continue;
      ++c.summary.motion_events;
      c.summary.program_time_s = time.end();
      if (std::holds_alternative<program::StraightTraverse>(event)) {
        c.timeline.push_back({time.start, block_index, std::nullopt, true, tool_change,
                              spindle_state(), program_s});
        tool_change = false;
        last_target.reset();
        last_air = true;
        evaluator.break_pass();
        sampler.add(event, c.summary.motion_events - 1, path);
        continue;
      }
      path.clear();
      sampler.add(event, c.summary.motion_events - 1, path);
      c.summary.cutting_time_s += time.duration;
      const float weight = path.empty() ? 0.0f
                                        : static_cast<float>(time.duration / static_cast<double>(path.size()));
      // The planner holds a block's S from its first sample on: a move that
      // continues the cut starts where the last one ended, at its target.
      if (!path.empty() && path.front().fraction > 0) {
        c.timeline.push_back({time.start, block_index, last_target, last_air, tool_change,
                              spindle_state(), program_s});
      }
      for (const auto& sample : path) {
        const auto r = evaluator.evaluate(sample);
        ++c.summary.samples;
        switch (r.contact.status) {
          case geometry::BallStatus::touching: ++c.summary.touching; break;
          case geometry::BallStatus::lifted: ++c.summary.lifted; break;
          case geometry::BallStatus::gouging: ++c.summary.gouging; break;
          case geometry::BallStatus::missed: ++c.summary.missed; break;
        }
        if (r.engagement) {
          switch (r.ae_source) {
            case pipeline::AeSource::measured: ++c.summary.ae_measured; break;
            case pipeline::AeSource::given: ++c.summary.ae_given; break;
            case pipeline::AeSource::first_pass: ++c.summary.ae_first_pass; break;
          }
        }
        std::optional<double> target = r.target_rpm;
        if (target && !std::isfinite(*target)) target = unbounded_rpm;
        // No vc to keep near the part (lifted in the air on an approach or a
        // link, or a plunge along the normal): like a rapid. Missed (far
        // from the model) keeps the program's S: not this finishing cut.
        const bool air = !target && r.contact.status != geometry::BallStatus::missed;
        c.timeline.push_back({time.start + time.duration * sample.fraction, block_index, target,
                              air, tool_change, spindle_state(), program_s});
        last_target = target;
        last_air = air;
        tool_change = false;
        c.samples.push_back({r.d_ref ? static_cast<float>(*r.d_ref) : NAN, weight,
                             static_cast<std::uint32_t>(block_index)});
        if (observer) {
          observer(sample, r, block_index, time.start + time.duration * sample.fraction, weight);
        }
      }
    }
    events.clear();
    if (progress && kind == ProgramKind::gcode && !c.blocks.empty() && !text.empty()) {
      const double done = static_cast<double>(c.blocks.back().offset) / static_cast<double>(text.size());
      if (done >= next_report) {
        progress(done);
        next_report = done + 0.01;
      }
    }
  }
  c.summary.blocks = c.blocks.size();
  return c;
}

std::optional<VcStatistics> vc_statistics(const std::vector<SampleInfo>& samples,
                                          const std::function<double(const SampleInfo&)>& rpm,
                                          double vc_nominal) {
  VcStatistics out{INFINITY, -INFINITY, 0, 0, 0};
  double weight = 0;
  for (const auto& s : samples) {
    if (std::isnan(s.d_ref) || s.weight_s <= 0) continue;
    const double vc = geometry::cutting_speed(s.d_ref, rpm(s));
    out.min = std::min(out.min, vc);
    out.max = std::max(out.max, vc);
    out.mean += s.weight_s * vc;
    const double deviation = std::abs(vc / vc_nominal - 1);
    if (deviation <= 0.05 + 1e-12) out.within_5_percent += s.weight_s;
    if (deviation <= 0.10 + 1e-12) out.within_10_percent += s.weight_s;
    weight += s.weight_s;
  }
  if (weight <= 0) return std::nullopt;
  out.mean /= weight;
  out.within_5_percent /= weight;
  out.within_10_percent /= weight;
  return out;
}

// S or F on the control's grid, rounded down so vc (or the feed per tooth)
// never exceeds the planned value.
double on_grid(double value, double step) { return std::floor(value / step + 1e-9) * step; }

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

ProgramKind detect_program_kind(std::string_view text) {
  // The first statement that is not blank or a comment decides.
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
    if (line.empty() || line.starts_with("$$") || line.front() == '(' || line.front() == ';' ||
        line.front() == '%') {
      continue;
    }
    std::string word;
    for (const char ch : line) {
      if (!std::isalpha(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_') break;
      word += static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    }
    const std::string_view rest = line.substr(word.size());
    const bool statement = word.size() >= 3 && rest.find_first_not_of(' ') != std::string_view::npos &&
                           rest[rest.find_first_not_of(' ')] == '/';
    if (statement || word == "PARTNO" || word == "FINI" || word == "TOOL" || word == "END") {
      return ProgramKind::cldata;
    }
    return ProgramKind::gcode;
  }
  return ProgramKind::gcode;
}

std::optional<geometry::Tool> tool_from_program(std::string_view text, const std::string& file_name) {
  if (detect_program_kind(text) != ProgramKind::cldata) return std::nullopt;
  ViewBuffer buffer(text);
  std::istream in(&buffer);
  cldata::ClReader reader(in, file_name);
  for (;;) {
    const auto event = reader.next();
    if (!reader.cutters().empty()) break;
    if (!event || program::is_motion(*event)) return std::nullopt;
  }
  const auto& cutter = reader.cutters().front();
  if (!cutter.tool) {
    throw PostError(file_name + ":" + std::to_string(cutter.source.line) + ": " +
                    cutter.source_word + " is not a ball, bull-nose or flat mill (" +
                    cutter.why_not + "); give --tool");
  }
  return cutter.tool;
}

PostSummary post_program(std::string_view text, const std::string& file_name,
                         const geometry::SurfaceModel& model,
                         const machines::MachineProfile& profile, const PostSettings& settings,
                         const std::function<void(std::string_view)>& sink,
                         const Progress& progress, const PointSink& points) {
  const ProgramKind kind = detect_program_kind(text);
  const gcode::Dialect dialect = settings.dialect.value_or(dialect_of(profile));
  EventSource source(text, file_name, kind, dialect);
  Collected c = collect(source, text, kind, model, profile, settings, progress);
  PostSummary summary = c.summary;

  const plan::SpindlePlan plan = plan_spindle(c.timeline, profile.spindle());
  // The plan block of each program block, and of the next block that has one.
  std::vector<int> own(c.blocks.size(), -1), next(c.blocks.size() + 1, -1);
  for (std::size_t i = 0; i < plan.blocks.size(); ++i) own[plan.blocks[i].block] = static_cast<int>(i);
  for (std::size_t b = c.blocks.size(); b-- > 0;) next[b] = own[b] >= 0 ? own[b] : next[b + 1];

  std::vector<plan::BlockFeed> feeds;
  if (settings.adjust_feed) {
    std::vector<plan::BlockFeedInput> inputs;
    for (const auto& block : plan.blocks) {
      inputs.push_back({c.blocks[block.block].program_f, c.blocks[block.block].program_s});
    }
    const double f_step = std::pow(10.0, -profile.output().feed_decimals);
    feeds = plan::plan_feeds(plan, inputs, settings.fz_mm,
                             settings.teeth.value_or(profile.tool().default_teeth), profile.feed(),
                             f_step);
  }
  const double s_step = profile.spindle().s_resolution_rpm;
  const int s_decimals = decimals_of(s_step);
  const int f_decimals = profile.output().feed_decimals;
  const double f_step = std::pow(10.0, -f_decimals);

  // S (F) in effect from block b on, when the plan changes it there: the
  // block's own S word if planned, else the next planned block's S for a
  // block that already carries an S word of the program.
  auto s_for = [&](std::size_t b) -> std::optional<double> {
    const int own_plan = own[b];
    if (own_plan >= 0 && plan.blocks[static_cast<std::size_t>(own_plan)].s_word) {
      return plan.blocks[static_cast<std::size_t>(own_plan)].planned_rpm;
    }
    if (!c.blocks[b].has_s || c.blocks[b].program_s <= 0 || next[b] < 0) return std::nullopt;
    const auto& target = plan.blocks[static_cast<std::size_t>(next[b])];
    if (target.bound == plan::Bound::off) return std::nullopt;
    return target.planned_rpm;
  };
  auto f_for = [&](std::size_t b) -> std::optional<double> {
    if (feeds.empty()) return std::nullopt;
    const int own_plan = own[b];
    if (own_plan >= 0 && plan.blocks[static_cast<std::size_t>(own_plan)].bound == plan::Bound::rapid) {
      return std::nullopt;  // rapids do not use F
    }
    if (own_plan >= 0 && feeds[static_cast<std::size_t>(own_plan)].f_word) {
      return feeds[static_cast<std::size_t>(own_plan)].f_mm_per_min;
    }
    if (!c.blocks[b].has_f || next[b] < 0) return std::nullopt;
    const auto& target = plan.blocks[static_cast<std::size_t>(next[b])];
    if (target.bound == plan::Bound::off || target.bound == plan::Bound::rapid) return std::nullopt;
    return feeds[static_cast<std::size_t>(next[b])].f_mm_per_min;
  };

  if (!sink) {
    // A dry run: nothing written.
  } else if (kind == ProgramKind::gcode) {
    std::vector<gcode::WordPatch> patches;
    for (std::size_t b = 0; b < c.blocks.size(); ++b) {
      if (const auto s = s_for(b)) {
        patches.push_back({c.blocks[b].offset, 'S', format_word(*s, s_step, s_decimals)});
        ++summary.s_words;
      }
      if (const auto f = f_for(b)) {
        patches.push_back({c.blocks[b].offset, 'F', format_word(*f, f_step, f_decimals)});
        ++summary.f_words;
      }
    }
    gcode::write_patched(text, patches, sink);
  } else {
    // CL: read again and write G-code in the profile's format, with the
    // planned S (F) before the motion of each block that changes it.
    std::ostringstream buffer;
    output::MazakFormat format;
    const auto& o = profile.output();
    format.program_number = o.program_number;
    format.high_speed_mode = o.high_speed_mode;
    format.geometry_compensation = o.geometry_compensation;
    format.work_offset = o.work_offset;
    format.decimals = o.decimals;
    format.feed_decimals = o.feed_decimals;
    format.line_numbers = o.line_numbers;
    output::MazakWriter writer(buffer, format);
    EventSource again(text, file_name, kind, dialect);
    BlockCounter counter(kind);
    std::vector<Event> events;
    while (again.next(events)) {
      for (Event& event : events) {
        const std::size_t block = counter.on(event).first;
        if (program::is_motion(event)) {
          if (const auto s = s_for(block); s && !c.blocks[block].has_s) {
            writer.write(program::SetSpindleSpeed{on_grid(*s, s_step), {}});
            ++summary.s_words;
          }
          if (const auto f = f_for(block); f && !c.blocks[block].has_f) {
            writer.write(program::SetFeedRate{on_grid(*f, f_step), program::FeedMode::per_minute, {}, std::nullopt});
            ++summary.f_words;
          }
        } else if (auto* s = std::get_if<program::SetSpindleSpeed>(&event)) {
          if (const auto planned = s_for(block)) s->rpm = on_grid(*planned, s_step);
        }
        writer.write(event);
      }
      events.clear();
      const std::string chunk = buffer.str();
      if (!chunk.empty()) sink(chunk);
      buffer.str({});
    }
    writer.finish();
    if (!buffer.str().empty()) sink(buffer.str());
  }

  for (const auto& block : plan.blocks) {
    const double duration = block.end_s - block.start_s;
    switch (block.bound) {
      case plan::Bound::n_max: summary.time_clamped_max_s += duration; break;
      case plan::Bound::n_min: summary.time_clamped_min_s += duration; break;
      case plan::Bound::slew: summary.time_slew_s += duration; break;
      case plan::Bound::rate: summary.time_rate_s += duration; break;
      default: break;
    }
  }
  // The S in effect on a block after the rewrite: its plan's, else the program's.
  auto after = [&](std::size_t b) {
    const int p = own[b];
    return p >= 0 ? plan.blocks[static_cast<std::size_t>(p)].planned_rpm : c.blocks[b].program_s;
  };
  const double vc = settings.point.vc;
  summary.before = vc_statistics(c.samples, [&](const SampleInfo& s) { return c.blocks[s.block].program_s; }, vc);
  summary.after = vc_statistics(c.samples, [&](const SampleInfo& s) { return after(s.block); }, vc);
  if (points) {
    EventSource again(text, file_name, kind, dialect);
    collect(again, text, kind, model, profile, settings, {},
            [&](const pipeline::PathSample& sample, const pipeline::PointResult& result,
                std::size_t block, double time_s, double weight_s) {
              const int p = own[block];
              points(sample, result,
                     PointRecord{sample.source.line, time_s, weight_s, c.blocks[block].program_s,
                                 after(block),
                                 p >= 0 ? plan.blocks[static_cast<std::size_t>(p)].bound
                                        : plan::Bound::program});
            });
  }
  if (progress) progress(1.0);
  return summary;
}

}  // namespace vcpost::post
