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
#include <span>
#include <thread>
#include <variant>
#include <vector>

#include "geometry/offset_model.h"
#include "postproc/cldata/cl_reader.h"
#include "postproc/gcode/block.h"
#include "postproc/plan/stop_aware_plan.h"
#include "postproc/plan/streaming_plan.h"
#include "postproc/post/offset_diagnosis.h"
#include "postproc/post/path_normal_reader.h"
#include "postproc/post/path_reader.h"
#include "postproc/post/program_writer.h"
#include "postproc/post/section_ledgers.h"
#include "postproc/post/speed_statistics.h"
#include "postproc/post/stock_timeline.h"
#include "postproc/post/tallies.h"

namespace vcpost::post {
namespace {

// Big enough to mean "no finite limit" to the planner (d_ref = 0).
constexpr double unbounded_rpm = 1e12;

// What the last stage keeps of an evaluated sample for the points sink
// (the statistics need only the HeldSample), until its block is final.
struct HeldPoint {
  pipeline::PathSample sample;
  pipeline::PointResult result;
};

// Blocks a pending section may hold back before it is kept as in the air
// (memory stays bounded on a long path that never touches).
constexpr std::size_t max_pending_blocks = 1 << 16;

// The planner the profile's control calls for: S words anywhere (inline), or
// only where the path stops anyway (spindle.stops_path_on_change).
class SpindlePlanner {
 public:
  explicit SpindlePlanner(const machines::SpindleSpec& spec) : planner_(make(spec)) {}
  void push(const plan::Sample& sample) {
    std::visit([&](auto& p) { p.push(sample); }, planner_);
  }
  void finish() {
    std::visit([](auto& p) { p.finish(); }, planner_);
  }
  void take_final(std::vector<plan::BlockPlan>& out) {
    std::visit([&](auto& p) { p.take_final(out); }, planner_);
  }

 private:
  using Any = std::variant<plan::StreamingPlanner, plan::StopAwarePlanner>;
  static Any make(const machines::SpindleSpec& spec) {
    if (spec.stops_path_on_change) return Any(std::in_place_type<plan::StopAwarePlanner>, spec);
    return Any(std::in_place_type<plan::StreamingPlanner>, spec);
  }
  Any planner_;
};

// The last, serial stage: follows the sections and counts the samples,
// feeds the planner, and as blocks become final writes them in order (those
// of a section not yet decided wait), hands their samples to the speed
// statistics and the points to the sink.
class Finisher {
 public:
  Finisher(const machines::MachineProfile& profile, const PostSettings& settings,
           ProgramWriter& writer, const PointSink& points, PostSummary& summary)
      : planner_(machines::planned_spindle(profile)),
        statistics_(machines::planned_spindle(profile), summary),
        sections_(summary, settings.point.contact_tolerance),
        writer_(writer),
        points_(points),
        summary_(summary) {
    if (settings.adjust_feed) {
      feeds_.emplace(settings.fz_mm, settings.teeth.value_or(profile.tool().default_teeth),
                     profile.feed(), std::pow(10.0, -profile.output().feed_decimals));
    }
  }

  // Whether the writer keeps the blocks of `section` as written.
  bool keeps(std::uint32_t section) const {
    return sections_.state(section) != SectionState::posted;
  }

  void take(Chunk& chunk) {
    writer_.add(chunk);
    for (ToolSection& section : chunk.sections) sections_.open(std::move(section));
    std::size_t sample_index = 0;
    for (Slot& slot : chunk.slots) {
      if (slot.section != current_) switch_section(slot.section);
      sections_.stamp(slot.section, slot.plan.time_s);
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
        case SlotKind::kept:
          kept(slot);
          break;
      }
      planner_.push(slot.plan);
    }
    planner_.take_final(final_);
    emit();
  }

  void finish() {
    switch_section(current_ + 1);  // the last section ends
    planner_.finish();
    planner_.take_final(final_);
    emit();
    release();
    writer_.finish();
    statistics_.finish();
    sections_.finish(writer_);
  }

 private:
  // The path moves on to `next`: a pending section that never touched is in the air.
  void switch_section(std::uint32_t next) {
    if (sections_.state(current_) == SectionState::pending) {
      sections_.keep(current_, "the path never touches the model: speed kept");
      release();
    }
    current_ = next;
  }

  void kept(Slot& slot) {
    sections_.count_kept(slot.section);
    slot.plan.target_rpm.reset();
    slot.plan.rapid = false;
    last_target_.reset();
    last_air_ = false;
  }

  void sample(Slot& slot, pipeline::PointResult& r) {
    ++summary_.samples;
    sections_.count_sample(slot.section, r.contact.status, r.contact.distance_error);
    if (slot.plan.spindle == plan::SpindleState::off &&
        (r.contact.status == geometry::BallStatus::touching ||
         r.contact.status == geometry::BallStatus::gouging) &&
        summary_.stopped_spindle_cuts++ == 0) {
      summary_.first_stopped_spindle_line = slot.sample.source.line;
    }
    if (summary_.stock) count_ap(r, slot.weight_s);
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

  // The stock's ap at an evaluated point, by band against --ap.
  void count_ap(const pipeline::PointResult& r, double weight_s) {
    StockSummary& s = *summary_.stock;
    switch (r.ap_source) {
      case pipeline::ApSource::given:
        if (r.engagement) ++s.points_given;
        return;
      case pipeline::ApSource::air:
        ++s.points_air;
        s.air_time_s += weight_s;
        return;
      case pipeline::ApSource::clamped:
        ++s.points_clamped;
        break;
      case pipeline::ApSource::stock:
        break;
    }
    ++s.points_stock;
    s.stock_time_s += weight_s;
    const double ratio = r.ap / s.nominal_ap_mm;
    std::size_t band = 0;
    while (band < kApBandLimits.size() && ratio > kApBandLimits[band]) ++band;
    s.band_time_s[band] += weight_s;
    if (ratio > 1) {
      ++s.over_nominal_points;
      s.over_nominal_time_s += weight_s;
    }
    s.ap_max_mm = std::max(s.ap_max_mm, r.ap);
  }

  // Final blocks go out in order; those of a pending section wait.
  void emit() {
    for (const plan::BlockPlan& block : final_) {
      if (!waiting_.empty() ||
          sections_.state(writer_.block(block.block).section) == SectionState::pending) {
        waiting_.push_back(block);
        continue;
      }
      write(block);
    }
    final_.clear();
    if (waiting_.size() > max_pending_blocks) {
      sections_.keep(writer_.block(waiting_.front().block).section,
                     "no point touches the model in its first " +
                         std::to_string(max_pending_blocks) + " blocks: speed kept");
    }
    release();
  }

  // Writes the waiting blocks whose section is decided.
  void release() {
    while (!waiting_.empty() && sections_.state(writer_.block(waiting_.front().block).section) !=
                                    SectionState::pending) {
      write(waiting_.front());
      waiting_.pop_front();
    }
    writer_.flush();
  }

  void write(const plan::BlockPlan& block) {
    statistics_.open_block(block);
    const BlockInfo& info = writer_.block(block.block);
    SectionLedger* ledger = sections_.ledger(info.section);
    std::optional<plan::BlockFeed> feed;
    if (feeds_) {
      feed = feeds_->next(block, {info.program_f, info.program_s, sections_.teeth(info.section)});
    }
    const double program_s = info.program_s;
    const bool posted = sections_.state(info.section) == SectionState::posted;
    if (feed && posted && block.target_rpm) {
      ++summary_.coupled_feed_blocks;
      if (feed->bound != plan::FeedBound::none) ++summary_.clamped_feed_blocks;
    }
    const double nominal = sections_.nominal_vc(info.section);
    while (!held_.empty() && held_.front().block <= block.block) {
      HeldSample& h = held_.front();
      if (posted) {
        statistics_.add_sample(h, program_s, block.planned_rpm, nominal, ledger->before,
                               ledger->after);
      }
      if (points_) {
        const HeldPoint& p = held_points_.front();
        points_(p.sample, p.result,
                PointRecord{p.sample.source.line, h.time_s, h.weight_s, program_s,
                            posted ? block.planned_rpm : program_s,
                            posted ? block.bound : plan::Bound::program, info.section,
                            sections_.tool(info.section)});
        held_points_.pop_front();
      }
      held_.pop_front();
    }
    if (posted) statistics_.add_bound_time(block);
    writer_.on_final(block, feed);
  }

  SpindlePlanner planner_;
  SpeedStatistics statistics_;
  SectionLedgers sections_;
  std::optional<plan::StreamingFeedPlanner> feeds_;
  ProgramWriter& writer_;
  const PointSink& points_;
  PostSummary& summary_;
  std::uint32_t current_ = 0;  // section of the last slot taken
  std::vector<plan::BlockPlan> final_;
  std::deque<plan::BlockPlan> waiting_;  // final, behind a pending section
  std::deque<HeldSample> held_;
  std::deque<HeldPoint> held_points_;
  std::optional<double> last_target_;  // of the last sample evaluated
  bool last_air_ = true;
};

}  // namespace

gcode::Dialect reading_dialect(const PostSettings& settings,
                               const machines::MachineProfile& profile) {
  return settings.dialect ? with_speed_output(*settings.dialect, profile) : dialect_of(profile);
}

verify::Options cl_output_verify_options(const machines::MachineProfile& profile) {
  verify::Options options;
  options.dialect = output_dialect_of(profile);
  options.speed_output = options.dialect.speed_output;
  options.output_decimals = profile.output().decimals;
  options.output_feed_decimals = profile.output().feed_decimals;
  options.cutter_compensation = profile.output().cutter_compensation;
  options.manual_tool_change = profile.output().tool_change == machines::ToolChange::manual;
  options.setups = profile.output().tilted_plane == machines::TiltedPlane::setup;
  return options;
}

namespace {

// The tools the job follows: settings.tools, or point.tool and point.vc for every tool.
tools::ToolChoices tools_of(const PostSettings& settings) {
  if (settings.tools) return *settings.tools;
  tools::ToolChoices choices;
  tools::ToolEntry every;
  const geometry::Tool& t = settings.point.tool;
  every.shape = t.kind == geometry::ToolKind::ball        ? tools::ToolShape::ball
                : t.kind == geometry::ToolKind::bull_nose ? tools::ToolShape::bull_nose
                                                          : tools::ToolShape::flat;
  every.diameter = t.diameter;
  every.corner_radius = t.corner_radius;
  every.name = geometry::to_string(t);
  choices.table.add(every);
  choices.vc = settings.point.vc;
  return choices;
}

}  // namespace

std::optional<ToolSection> first_postable_section(std::string_view text,
                                                  const std::string& file_name,
                                                  const machines::MachineProfile& profile,
                                                  const PostSettings& settings) {
  const gcode::Dialect dialect = reading_dialect(settings, profile);
  const ProgramKind kind = program_kind(text, dialect);
  const tools::ToolChoices choices = tools_of(settings);
  PathReader reader(text, file_name, kind, dialect, profile, settings.sample_spacing_mm, false,
                    choices, settings.point.ap);
  reader.set_program_loader(settings.program_loader);
  Chunk chunk;
  while (reader.read(chunk, chunk_samples)) {
    for (const ToolSection& section : chunk.sections) {
      if (section.postable) return section;
    }
  }
  return std::nullopt;
}

namespace {

// The threads of one run: PostSettings::threads, 0 for one per core. More
// than cores: oneTBB caps its workers at the core count by default (and
// warns on stderr), so the cap is lifted while this lives.
class RunThreads {
 public:
  explicit RunThreads(int asked) {
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    count_ = asked > 0 ? asked : cores;
    if (count_ > cores) parallelism_.emplace(tbb::global_control::max_allowed_parallelism, count_);
  }
  int count() const { return count_; }

 private:
  int count_ = 1;
  std::optional<tbb::global_control> parallelism_;
};

}  // namespace

PathNormalsAhead read_path_normals(std::string_view text, const std::string& file_name,
                                   const machines::MachineProfile& profile,
                                   const PostSettings& settings) {
  const gcode::Dialect dialect = reading_dialect(settings, profile);
  const ProgramKind kind = program_kind(text, dialect);
  const RunThreads threads(settings.threads);  // as post_program runs it
  tbb::task_arena arena(threads.count());
  PathNormalsAhead ahead;
  arena.execute([&] {
    ahead =
        normals_from_path(text, file_name, kind, dialect, profile, settings, tools_of(settings));
  });
  return ahead;
}

namespace {

// One evaluator per posted section (its own tool, vc and passes), made by
// the reading stage as sections appear; each chunk carries pointers to the
// evaluators of its sections to the other stages.
class SectionEvaluators {
 public:
  SectionEvaluators(const geometry::SurfaceModel& model, const pipeline::PointSettings& point,
                    bool cutting_points, const StockTimeline* stock)
      : model_(model), point_(point), cutting_points_(cutting_points), stock_(stock) {}

  void attach(Chunk& chunk) {
    for (const ToolSection& section : chunk.sections) {
      if (evaluators_.size() <= section.index) evaluators_.resize(section.index + 1);
      if (!section.postable) continue;
      pipeline::PointSettings point_settings = point_;
      point_settings.tool = *section.entry->geometry();
      point_settings.vc = section.vc_nominal;
      point_settings.cutting_points = cutting_points_;  // only the report reads them
      evaluators_[section.index] =
          std::make_unique<pipeline::PointEvaluator>(model_for(section), point_settings);
      // Material thinner than the contact tolerance is taken as none.
      if (stock_ != nullptr)
        evaluators_[section.index]->set_material(stock_->before(section.index),
                                                 point_.contact_tolerance);
    }
    std::uint32_t last = chunk.first_section;
    for (const Slot& slot : chunk.slots) last = std::max(last, slot.section);
    if (evaluators_.size() <= last) evaluators_.resize(last + 1);
    chunk.evaluators.clear();
    for (std::uint32_t section = chunk.first_section; section <= last; ++section)
      chunk.evaluators.push_back(evaluators_[section].get());
  }

 private:
  // The surface the section's tool touches: the model, or the model offset
  // by the section's allowance (contact, ae and the engagement are then all
  // measured on the offset surface).
  const geometry::SurfaceModel& model_for(const ToolSection& section) {
    if (section.stock.is_zero()) return model_;
    // Not owned: the job's model outlives every evaluator.
    const std::shared_ptr<const geometry::SurfaceModel> base(std::shared_ptr<void>(), &model_);
    offset_models_.push_back(std::make_unique<geometry::OffsetModel>(base, section.stock));
    return *offset_models_.back();
  }

  const geometry::SurfaceModel& model_;
  const pipeline::PointSettings& point_;
  bool cutting_points_;
  const StockTimeline* stock_;
  std::vector<std::unique_ptr<geometry::OffsetModel>> offset_models_;
  std::vector<std::unique_ptr<pipeline::PointEvaluator>> evaluators_;
};

// The chunks of the pipeline: every chunk in flight holds a token, so one
// chunk per token suffices; they are reused, and their vectors keep their
// capacity.
class ChunkPool {
 public:
  explicit ChunkPool(std::size_t tokens) {
    for (std::size_t i = 0; i < tokens; ++i) {
      chunks_.push_back(std::make_unique<Chunk>());
      free_.push_back(chunks_.back().get());
    }
  }
  Chunk* take() {
    std::lock_guard lock(mutex_);
    Chunk* chunk = free_.back();
    free_.pop_back();
    return chunk;
  }
  void give(Chunk* chunk) {
    std::lock_guard lock(mutex_);
    free_.push_back(chunk);
  }

 private:
  std::vector<std::unique_ptr<Chunk>> chunks_;
  std::vector<Chunk*> free_;
  std::mutex mutex_;
};

// The totals only the reader and the writer know.
void add_totals(PostSummary& summary, const PathReader& reader, const ProgramWriter& writer) {
  const ReadTotals& totals = reader.totals();
  summary.blocks = totals.blocks;
  summary.motion_events = totals.motion_events;
  summary.program_time_s = totals.program_time_s;
  summary.cutting_time_s = totals.cutting_time_s;
  summary.s_words = writer.s_words();
  summary.f_words = writer.f_words();
  summary.tool_notes = reader.tool_notes();
  summary.repeated_lines = writer.repeated_lines();
  summary.missing_end = totals.missing_end;
  summary.unread_after_end = totals.unread_after_end;
}

// What the job reads of the program before its own read, in its arena.
struct ReadAhead {
  // The normals from the path itself (PostSettings::normals_from_path):
  // read by the caller (read_path_normals), or here.
  std::shared_ptr<const PathNormalsAhead> path_normals;
  std::unique_ptr<StockTimeline> stock;  // PostSettings::stock
};

ReadAhead read_ahead(std::string_view text, const std::string& file_name, ProgramKind kind,
                     const gcode::Dialect& dialect, const machines::MachineProfile& profile,
                     const PostSettings& settings, const tools::ToolChoices& choices,
                     tbb::task_arena& arena, PostSummary& summary) {
  ReadAhead ahead;
  if (settings.normals_from_path) {
    ahead.path_normals = settings.path_normals;
    if (!ahead.path_normals) {
      arena.execute([&] {
        ahead.path_normals = std::make_shared<const PathNormalsAhead>(
            normals_from_path(text, file_name, kind, dialect, profile, settings, choices));
      });
    }
    summary.path_normals = pipeline::count_sources(ahead.path_normals->normals);
  }
  if (settings.stock) {
    arena.execute([&] {
      ahead.stock =
          build_stock_timeline(text, file_name, kind, dialect, profile, settings, choices);
    });
    summary.stock = ahead.stock->summary();
  }
  return ahead;
}

// The job's pipeline over the chunks: read (serial), contact (parallel),
// place (serial: the passes follow the path), engage (parallel), finish
// (serial, in order).
class Stages {
 public:
  Stages(PathReader& reader, SectionEvaluators& evaluators, Finisher& finisher,
         const PathNormalsAhead* path_normals, bool curvature, ProgramKind kind,
         const Progress& progress, const std::function<void(std::uint64_t)>& consumed,
         std::size_t tokens)
      : reader_(reader),
        evaluators_(evaluators),
        finisher_(finisher),
        path_normals_(path_normals),
        curvature_(curvature),
        kind_(kind),
        progress_(progress),
        consumed_(consumed),
        tokens_(tokens),
        pool_(tokens) {}

  void run(tbb::task_arena& arena) {
    arena.execute([&] {
      tbb::parallel_pipeline(
          tokens_,
          tbb::make_filter<void, Chunk*>(tbb::filter_mode::serial_in_order,
                                         [this](tbb::flow_control& c) { return read(c); }) &
              tbb::make_filter<Chunk*, Chunk*>(tbb::filter_mode::parallel,
                                               [this](Chunk* c) { return contact(c); }) &
              tbb::make_filter<Chunk*, Chunk*>(tbb::filter_mode::serial_in_order,
                                               [this](Chunk* c) { return place(c); }) &
              tbb::make_filter<Chunk*, Chunk*>(tbb::filter_mode::parallel,
                                               [this](Chunk* c) { return engage(c); }) &
              tbb::make_filter<Chunk*, void>(tbb::filter_mode::serial_in_order,
                                             [this](Chunk* c) { finish(c); }));
    });
  }

 private:
  Chunk* read(tbb::flow_control& control) {
    Chunk* chunk = pool_.take();
    if (!reader_.read(*chunk, chunk_samples)) {
      control.stop();
      return nullptr;
    }
    evaluators_.attach(*chunk);
    chunk->first_sample = samples_read_;
    for (const Slot& slot : chunk->slots) samples_read_ += slot.kind == SlotKind::sample ? 1 : 0;
    if (kind_ == ProgramKind::cldata && consumed_) consumed_(chunk->read_bytes);
    return chunk;
  }

  Chunk* contact(Chunk* chunk) const {
    geometry::ContactHint hint;  // cold at the chunk's start
    hint.curvature = curvature_;
    chunk->results.clear();  // keeps its capacity
    std::uint64_t sample = chunk->first_sample;
    for (const Slot& slot : chunk->slots) {
      if (slot.kind != SlotKind::sample) continue;
      const pipeline::PointEvaluator& evaluator = *chunk->evaluator(slot.section);
      pipeline::PointResult& result = chunk->results.emplace_back();
      if (path_normals_ != nullptr) {
        const pipeline::PathNormal& normal = path_normals_->normals.at(sample++);
        result.contact = evaluator.contact(slot.sample, normal);
        result.normal_source = normal.source;
      } else {
        result.contact = evaluator.contact(slot.sample, hint);
      }
    }
    return chunk;
  }

  Chunk* place(Chunk* chunk) const {
    std::size_t sample_index = 0;
    for (const Slot& slot : chunk->slots) {
      pipeline::PointEvaluator* evaluator = chunk->evaluator(slot.section);
      if (evaluator == nullptr) continue;  // a section not posted: no pass, no sample
      if (slot.break_pass) evaluator->break_pass();
      if (slot.kind != SlotKind::sample) continue;
      pipeline::PointResult& result = chunk->results[sample_index];
      if (path_normals_ != nullptr) {
        // The earlier pass the normals' read-ahead found: no second tracker.
        evaluator->place(slot.sample, result,
                         path_normals_->earlier.at(chunk->first_sample + sample_index));
      } else {
        evaluator->place(slot.sample, result);
      }
      ++sample_index;
    }
    return chunk;
  }

  static Chunk* engage(Chunk* chunk) {
    std::size_t sample_index = 0;
    for (const Slot& slot : chunk->slots) {
      if (slot.kind == SlotKind::sample)
        chunk->evaluator(slot.section)->engage(slot.sample, chunk->results[sample_index++]);
    }
    return chunk;
  }

  void finish(Chunk* chunk) {
    finisher_.take(*chunk);
    if (progress_ && chunk->read_fraction >= next_report_) {
      progress_(std::min(chunk->read_fraction, 1.0));
      next_report_ = chunk->read_fraction + 0.01;
    }
    pool_.give(chunk);
  }

  PathReader& reader_;
  SectionEvaluators& evaluators_;
  Finisher& finisher_;
  const PathNormalsAhead* path_normals_;  // without a model: the normals read ahead
  bool curvature_;                        // only the report's points read curvatures
  ProgramKind kind_;
  const Progress& progress_;
  const std::function<void(std::uint64_t)>& consumed_;
  std::size_t tokens_;
  ChunkPool pool_;
  std::uint64_t samples_read_ = 0;
  double next_report_ = 0.01;
};

}  // namespace

PostSummary post_program(std::string_view text, const std::string& file_name,
                         const geometry::SurfaceModel& model,
                         const machines::MachineProfile& profile, const PostSettings& settings,
                         const std::function<void(std::string_view)>& sink,
                         const Progress& progress, const PointSink& points,
                         const std::function<void(std::uint64_t)>& consumed) {
  const gcode::Dialect dialect = reading_dialect(settings, profile);
  const ProgramKind kind = program_kind(text, dialect);
  PostSummary summary;
  summary.kind = kind;
  const tools::ToolChoices choices = tools_of(settings);
  PathReader reader(text, file_name, kind, dialect, profile, settings.sample_spacing_mm,
                    kind == ProgramKind::cldata, choices, settings.point.ap);
  reader.set_program_loader(settings.program_loader);
  // The writer releases G-code text behind it; CL text is done with once read.
  const Finisher* decides = nullptr;  // set below: the writer asks it which sections it keeps
  ProgramWriter writer(
      text, kind, profile, settings.adjust_feed, sink,
      kind != ProgramKind::cldata ? consumed : std::function<void(std::uint64_t)>{},
      [&decides](std::uint32_t section) { return decides->keeps(section); });
  Finisher finisher(profile, settings, writer, points, summary);
  decides = &finisher;

  const RunThreads run_threads(settings.threads);
  const int threads = run_threads.count();
  // Chunks in flight: enough to keep every thread busy, few enough to bound memory.
  const std::size_t tokens = 2 * static_cast<std::size_t>(threads) + 2;
  tbb::task_arena arena(threads);
  const ReadAhead ahead =
      read_ahead(text, file_name, kind, dialect, profile, settings, choices, arena, summary);
  SectionEvaluators evaluators(model, settings.point, static_cast<bool>(points), ahead.stock.get());
  Stages stages(reader, evaluators, finisher, ahead.path_normals.get(), static_cast<bool>(points),
                kind, progress, consumed, tokens);
  stages.run(arena);
  finisher.finish();
  add_totals(summary, reader, writer);
  if (progress) progress(1.0);
  return summary;
}

}  // namespace vcpost::post
