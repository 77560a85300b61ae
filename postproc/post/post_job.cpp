#include "postproc/post/post_job.h"

#include <tbb/global_control.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <istream>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "postproc/cldata/cl_reader.h"
#include "postproc/plan/streaming_plan.h"
#include "postproc/post/path_reader.h"
#include "postproc/post/program_writer.h"

namespace vcpost::post {
namespace {

// Big enough to mean "no finite limit" to the planner (d_ref = 0).
constexpr double unbounded_rpm = 1e12;

// Path samples per chunk: the unit of work of the threads. Contact queries
// start cold at every chunk (so results do not depend on the number of
// threads), which costs little at this size.
constexpr std::size_t chunk_samples = 2048;

// Cutting-speed statistics, accumulated sample by sample.
class VcAccumulator {
 public:
  explicit VcAccumulator(double vc_nominal) : nominal_(vc_nominal) {}
  void add(double d_ref, double weight_s, double rpm) {
    if (std::isnan(d_ref) || weight_s <= 0) return;
    const double vc = geometry::cutting_speed(d_ref, rpm);
    out_.min = std::min(out_.min, vc);
    out_.max = std::max(out_.max, vc);
    out_.mean += weight_s * vc;
    const double deviation = std::abs(vc / nominal_ - 1);
    if (deviation <= 0.05 + 1e-12) out_.within_5_percent += weight_s;
    if (deviation <= 0.10 + 1e-12) out_.within_10_percent += weight_s;
    weight_ += weight_s;
  }
  std::optional<VcStatistics> result() const {
    if (weight_ <= 0) return std::nullopt;
    VcStatistics r = out_;
    r.mean /= weight_;
    r.within_5_percent /= weight_;
    r.within_10_percent /= weight_;
    return r;
  }

 private:
  double nominal_;
  VcStatistics out_{INFINITY, -INFINITY, 0, 0, 0};
  double weight_ = 0;
};

// What the last stage keeps of an evaluated sample until its block is final.
struct HeldSample {
  float d_ref = NAN;  // mm; NaN where the tool does not cut
  float weight_s = 0;
  std::size_t block = 0;
  double time_s = 0;
};
// ... and for the points sink, the whole point.
struct HeldPoint {
  pipeline::PathSample sample;
  pipeline::PointResult result;
};

// The last, serial stage: counts, feeds the planner, and as blocks become
// final writes them, accumulates the statistics and hands out the points.
class Finisher {
 public:
  Finisher(const machines::MachineProfile& profile, const PostSettings& settings,
           ProgramWriter& writer, const PointSink& points, PostSummary& summary)
      : planner_(profile.spindle()),
        writer_(writer),
        points_(points),
        summary_(summary),
        before_(settings.point.vc),
        after_(settings.point.vc) {
    if (settings.adjust_feed) {
      feeds_.emplace(settings.fz_mm, settings.teeth.value_or(profile.tool().default_teeth),
                     profile.feed(), std::pow(10.0, -profile.output().feed_decimals));
    }
  }

  void take(Chunk& chunk) {
    writer_.add(chunk);
    std::size_t sample_index = 0;
    for (Slot& slot : chunk.slots) {
      switch (slot.kind) {
        case SlotKind::rapid:
          last_target_.reset();
          last_air_ = true;
          break;
        case SlotKind::resume:
          slot.plan.target_rpm = last_target_;
          slot.plan.rapid = last_air_;
          break;
        case SlotKind::sample:
          sample(slot, chunk.results[sample_index++]);
          break;
      }
      planner_.push(slot.plan);
    }
    planner_.take_final(final_);
    emit();
  }

  void finish() {
    planner_.finish();
    planner_.take_final(final_);
    emit();
    writer_.finish();
    summary_.before = before_.result();
    summary_.after = after_.result();
  }

 private:
  void sample(Slot& slot, pipeline::PointResult& r) {
    ++summary_.samples;
    switch (r.contact.status) {
      case geometry::BallStatus::touching:
        ++summary_.touching;
        break;
      case geometry::BallStatus::lifted:
        ++summary_.lifted;
        break;
      case geometry::BallStatus::gouging:
        ++summary_.gouging;
        break;
      case geometry::BallStatus::missed:
        ++summary_.missed;
        break;
    }
    if (r.engagement) {
      switch (r.ae_source) {
        case pipeline::AeSource::measured:
          ++summary_.ae_measured;
          break;
        case pipeline::AeSource::given:
          ++summary_.ae_given;
          break;
        case pipeline::AeSource::first_pass:
          ++summary_.ae_first_pass;
          break;
      }
    }
    // No vc to keep near the part (lifted in the air on an approach or a
    // link, or a plunge along the normal): like a rapid. Missed (far from
    // the model) keeps the program's S: not this finishing cut.
    const bool air = !r.target_rpm && r.contact.status != geometry::BallStatus::missed;
    // Set from the plain value, not copied as an optional: a copy of one
    // just written stalls the store forwarding, and this runs per sample.
    if (r.target_rpm) {
      const double target = std::isfinite(*r.target_rpm) ? *r.target_rpm : unbounded_rpm;
      slot.plan.target_rpm = target;
      last_target_ = target;
    } else {
      slot.plan.target_rpm.reset();
      last_target_.reset();
    }
    slot.plan.rapid = air;
    last_air_ = air;
    held_.push_back({r.d_ref ? static_cast<float>(*r.d_ref) : NAN, slot.weight_s, slot.plan.block,
                     slot.plan.time_s});
    if (points_) held_points_.push_back({slot.sample, std::move(r)});
  }

  void emit() {
    for (const plan::BlockPlan& block : final_) {
      const BlockInfo& info = writer_.block(block.block);
      std::optional<plan::BlockFeed> feed;
      if (feeds_) feed = feeds_->next(block, {info.program_f, info.program_s});
      const double program_s = info.program_s;
      while (!held_.empty() && held_.front().block <= block.block) {
        HeldSample& h = held_.front();
        before_.add(h.d_ref, h.weight_s, program_s);
        after_.add(h.d_ref, h.weight_s, block.planned_rpm);
        if (points_) {
          const HeldPoint& p = held_points_.front();
          points_(p.sample, p.result,
                  PointRecord{p.sample.source.line, h.time_s, h.weight_s, program_s,
                              block.planned_rpm, block.bound});
          held_points_.pop_front();
        }
        held_.pop_front();
      }
      const double duration = block.end_s - block.start_s;
      switch (block.bound) {
        case plan::Bound::n_max:
          summary_.time_clamped_max_s += duration;
          break;
        case plan::Bound::n_min:
          summary_.time_clamped_min_s += duration;
          break;
        case plan::Bound::slew:
          summary_.time_slew_s += duration;
          break;
        case plan::Bound::rate:
          summary_.time_rate_s += duration;
          break;
        default:
          break;
      }
      writer_.on_final(block, feed);
    }
    writer_.flush();
    final_.clear();
  }

  plan::StreamingPlanner planner_;
  std::optional<plan::StreamingFeedPlanner> feeds_;
  ProgramWriter& writer_;
  const PointSink& points_;
  PostSummary& summary_;
  VcAccumulator before_, after_;
  std::vector<plan::BlockPlan> final_;
  std::deque<HeldSample> held_;
  std::deque<HeldPoint> held_points_;
  std::optional<double> last_target_;  // of the last sample evaluated
  bool last_air_ = true;
};

}  // namespace

gcode::Dialect dialect_of(const machines::MachineProfile& profile) {
  switch (profile.dialect()) {
    case machines::Dialect::fanuc:
      return gcode::fanuc_dialect();
    case machines::Dialect::mazak:
      return gcode::mazak_dialect();
    case machines::Dialect::rs274ngc:
      break;
  }
  return gcode::rs274ngc_dialect();
}

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
    const bool statement = word.size() >= 3 &&
                           rest.find_first_not_of(' ') != std::string_view::npos &&
                           rest[rest.find_first_not_of(' ')] == '/';
    if (statement || word == "PARTNO" || word == "FINI" || word == "TOOL" || word == "END") {
      return ProgramKind::cldata;
    }
    return ProgramKind::gcode;
  }
  return ProgramKind::gcode;
}

std::optional<geometry::Tool> tool_from_program(std::string_view text,
                                                const std::string& file_name) {
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
                         const Progress& progress, const PointSink& points,
                         const std::function<void(std::uint64_t)>& consumed) {
  const ProgramKind kind = detect_program_kind(text);
  const gcode::Dialect dialect = settings.dialect.value_or(dialect_of(profile));
  PostSummary summary;
  summary.kind = kind;

  PathReader reader(text, file_name, kind, dialect, profile, settings.sample_spacing_mm,
                    kind == ProgramKind::cldata);
  // The writer releases G-code text behind it; CL text is done with once read.
  ProgramWriter writer(
      text, kind, profile, settings.adjust_feed, sink,
      kind == ProgramKind::gcode ? consumed : std::function<void(std::uint64_t)>{});
  pipeline::PointSettings point_settings = settings.point;
  point_settings.cutting_points = static_cast<bool>(points);  // only the report's points read them
  pipeline::PointEvaluator evaluator(model, point_settings);
  Finisher finisher(profile, settings, writer, points, summary);

  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = settings.threads > 0 ? settings.threads : cores;
  // More threads than cores: oneTBB caps its workers at the core count by
  // default (and warns on stderr); lift the cap for this run.
  std::optional<tbb::global_control> parallelism;
  if (threads > cores) parallelism.emplace(tbb::global_control::max_allowed_parallelism, threads);
  // Chunks in flight: enough to keep every thread busy, few enough to bound memory.
  const auto tokens = static_cast<std::size_t>(2 * threads + 2);
  // Every chunk in flight holds a token, so `tokens` chunks suffice; they
  // are reused, and their vectors keep their capacity.
  std::vector<std::unique_ptr<Chunk>> chunks;
  std::vector<Chunk*> free_chunks;
  for (std::size_t i = 0; i < tokens; ++i) {
    chunks.push_back(std::make_unique<Chunk>());
    free_chunks.push_back(chunks.back().get());
  }
  std::mutex free_mutex;
  double next_report = 0.01;

  auto read = [&](tbb::flow_control& control) -> Chunk* {
    Chunk* chunk = nullptr;
    {
      std::lock_guard lock(free_mutex);
      chunk = free_chunks.back();
      free_chunks.pop_back();
    }
    if (!reader.read(*chunk, chunk_samples)) {
      control.stop();
      return nullptr;
    }
    if (kind == ProgramKind::cldata && consumed) consumed(chunk->read_bytes);
    return chunk;
  };
  auto contact = [&](Chunk* chunk) -> Chunk* {
    geometry::ContactHint hint;                  // cold at the chunk's start
    hint.curvature = static_cast<bool>(points);  // only the report's points read curvatures
    chunk->results.clear();                      // keeps its capacity
    for (const Slot& slot : chunk->slots) {
      if (slot.kind == SlotKind::sample)
        chunk->results.emplace_back().contact = evaluator.contact(slot.sample, hint);
    }
    return chunk;
  };
  auto place = [&](Chunk* chunk) -> Chunk* {
    std::size_t sample_index = 0;
    for (const Slot& slot : chunk->slots) {
      if (slot.break_pass) evaluator.break_pass();
      if (slot.kind == SlotKind::sample)
        evaluator.place(slot.sample, chunk->results[sample_index++]);
    }
    return chunk;
  };
  auto engage = [&](Chunk* chunk) -> Chunk* {
    std::size_t sample_index = 0;
    for (const Slot& slot : chunk->slots) {
      if (slot.kind == SlotKind::sample)
        evaluator.engage(slot.sample, chunk->results[sample_index++]);
    }
    return chunk;
  };
  auto finish = [&](Chunk* chunk) {
    finisher.take(*chunk);
    if (progress && chunk->read_fraction >= next_report) {
      progress(std::min(chunk->read_fraction, 1.0));
      next_report = chunk->read_fraction + 0.01;
    }
    std::lock_guard lock(free_mutex);
    free_chunks.push_back(chunk);
  };

  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_pipeline(
        tokens, tbb::make_filter<void, Chunk*>(tbb::filter_mode::serial_in_order, read) &
                    tbb::make_filter<Chunk*, Chunk*>(tbb::filter_mode::parallel, contact) &
                    tbb::make_filter<Chunk*, Chunk*>(tbb::filter_mode::serial_in_order, place) &
                    tbb::make_filter<Chunk*, Chunk*>(tbb::filter_mode::parallel, engage) &
                    tbb::make_filter<Chunk*, void>(tbb::filter_mode::serial_in_order, finish));
  });
  finisher.finish();

  const ReadTotals& totals = reader.totals();
  summary.blocks = totals.blocks;
  summary.motion_events = totals.motion_events;
  summary.program_time_s = totals.program_time_s;
  summary.cutting_time_s = totals.cutting_time_s;
  summary.s_words = writer.s_words();
  summary.f_words = writer.f_words();
  if (progress) progress(1.0);
  return summary;
}

}  // namespace vcpost::post
