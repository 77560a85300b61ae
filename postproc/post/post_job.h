// `vcpost post` as a library call: the input program with its S words (and
// F words, with feed coupling) rewritten so the cutting speed at the
// reference working diameter stays at its nominal value, within what the
// machine profile allows. No I/O: text in, text out through a sink.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "geometry/model.h"
#include "machines/profile.h"
#include "postproc/gcode/dialect.h"
#include "postproc/heidenhain/program_loader.h"
#include "postproc/pipeline/point_evaluator.h"
#include "postproc/plan/spindle_plan.h"
#include "postproc/post/program_kind.h"
#include "postproc/post/stock_source.h"
#include "postproc/post/stock_summary.h"
#include "postproc/post/tool_sections.h"
#include "postproc/tools/tool_table.h"
#include "postproc/verify/verify.h"

namespace vcpost::post {

// How `vcpost verify` reads the G-code vcpost wrote from CL data for the
// profile: its output dialect, grid (decimals), cutter compensation and
// tool change form. The tolerance stays the default.
verify::Options cl_output_verify_options(const machines::MachineProfile& profile);

// Without a model: the normal at every sample of the posted sections, in
// path order (path_normal_reader.h), the earlier pass beside it (its width
// of cut is measured to), and the bounds of those samples' programmed
// points (empty: none).
struct PathNormalsAhead {
  std::vector<pipeline::PathNormal> normals;
  std::vector<pipeline::EarlierPass> earlier;
  Eigen::AlignedBox3d bounds;
};

struct PostSettings {
  // Every posted section's settings but its tool and vc, which come from
  // `tools` section by section. Without `tools`, point.tool is every
  // tool's and point.vc every tool's vc (the program's own tools unread).
  pipeline::PointSettings point;
  std::optional<tools::ToolChoices> tools;
  double sample_spacing_mm = 0.5;         // largest distance between evaluated points
  std::optional<gcode::Dialect> dialect;  // G-code input; default: the profile's
  bool adjust_feed = false;               // couple F = fz * z * n
  std::optional<double> fz_mm;            // feed per tooth; default: the program's F at its S
  std::optional<int> teeth;               // tools without their own; default: the profile's
  int threads = 0;                        // worker threads; 0: one per core
  // Klartext: how CALL PGM finds the called program (none: refused, E3331).
  heidenhain::ProgramLoader program_loader;
  // No model: each sample's normal from the toolpath itself
  // (pipeline/path_normals.h); the model passed is not read. No gouge
  // check (every normal found touches), no cusp map.
  bool normals_from_path = false;
  // With normals_from_path: the normals read ahead by the caller
  // (read_path_normals) for the same text and settings; empty: the job
  // reads them itself.
  std::shared_ptr<const PathNormalsAhead> path_normals;
  // An in-process stock (docs/stock.md): ap at each untilted point of the
  // evaluated sections from the material the earlier sections left, instead
  // of point.ap; none: point.ap everywhere.
  std::optional<StockSettings> stock;
};

// The dialect the job reads its G-code input in: --dialect
// (PostSettings::dialect) or the profile's, with the profile's speed output
// (output.speed_word) for an rs274ngc program.
gcode::Dialect reading_dialect(const PostSettings& settings,
                               const machines::MachineProfile& profile);

// How the S words sit on this machine's control, per section of the
// program (a run of the spindle: from a start, a tool change or a reversal
// of the spindle to the next), and what they cost in path time.
struct SectionPlacement {
  std::size_t run = 0;        // the planner's run index
  double start_s = 0;         // program time of its first block
  double cutting_time_s = 0;  // cutting time of its evaluated points
  std::uint64_t s_words = 0;  // S words the plan placed
  std::uint64_t in_feed = 0;  // of them inside a feed stream (not where the path stops anyway)
  std::uint64_t stops = 0;    // of them that stop the path on this control
  double time_cost_s = 0;     // stops x the profile's stop cost
  std::optional<VcStatistics> before, after;
};

struct SPlacement {
  bool at_stops = false;   // the control stops the path at an S word: words only at stops
  bool priced = false;     // ... and in feed streams where worth the stop (spindle.s_in_feed)
  double stop_cost_s = 0;  // the profile's cost of one stop
  std::uint64_t s_words = 0, in_feed = 0, stops = 0;
  double time_cost_s = 0;
  std::vector<SectionPlacement> sections;
};

// The evaluated samples by contact state are the ContactCounts it derives from.
struct PostSummary : ContactCounts {
  ProgramKind kind = ProgramKind::gcode;
  std::uint64_t blocks = 0, motion_events = 0, samples = 0;
  std::uint64_t ae_measured = 0, ae_given = 0, ae_first_pass = 0;
  double program_time_s = 0, cutting_time_s = 0;
  std::uint64_t s_words = 0, f_words = 0;
  // Lines that ran more than once (subroutines, loops, M98) with an S or F
  // decided on each run: written once, with the lowest of the values.
  std::uint64_t repeated_lines = 0;
  // Evaluated points that touch or gouge the model with the spindle stopped
  // (S0, M5, CL SPINDL/0 or OFF), and the line of the first (W2030).
  std::uint64_t stopped_spindle_cuts = 0;
  // --adjust-feed: cutting blocks of posted sections with a coupled F, and
  // of them those whose F the profile's f_min or f_max decided (W2032).
  std::uint64_t coupled_feed_blocks = 0, clamped_feed_blocks = 0;
  std::uint32_t first_stopped_spindle_line = 0;
  bool missing_end = false;      // G-code: no M2/M30 or closing '%' (a truncated file?)
  std::string unread_after_end;  // G-code: lines after the closing '%' (the warning), or ""
  // Cutting time (s) of the blocks whose planned S each bound decided.
  double time_clamped_max_s = 0, time_clamped_min_s = 0, time_slew_s = 0, time_rate_s = 0;
  // Over the posted sections, each at its own nominal vc; empty when no sample cut.
  std::optional<VcStatistics> before, after;
  std::vector<ToolSection> sections;    // every section with a motion, in program order
  std::vector<std::string> tool_notes;  // tool comments that could not be read
  SPlacement s_placement;               // how the S words sit on the control and what they cost
  // Without a model (PostSettings::normals_from_path): how the normal of
  // each sample of the posted sections was found.
  std::optional<pipeline::PathNormalCounts> path_normals;
  // With PostSettings::stock: the stock and the ap it gave.
  std::optional<StockSummary> stock;
};

// One evaluated point of the path with the spindle speed before (the
// program's) and after (the plan's), for reports.
struct PointRecord {
  std::uint32_t line = 0;                             // NC line (CL record) of the block
  double time_s = 0;                                  // from program start
  double weight_s = 0;                                // cutting time the point stands for
  double s_before = 0, s_after = 0;                   // rpm in effect
  plan::Bound bound = plan::Bound::none;              // what decided s_after
  std::uint32_t section = 0;                          // ToolSection::index
  std::optional<geometry::Tool> tool = std::nullopt;  // the section's, where it has one
};
using PointSink = std::function<void(const pipeline::PathSample&, const pipeline::PointResult&,
                                     const PointRecord&)>;

// Progress: fraction of the input read, in [0, 1].
using Progress = std::function<void(double)>;

// The first section the job would evaluate (a postable tool, see
// tool_sections.h), read ahead without evaluating anything: for what must be
// known before the run (the report's tool). Empty when no section is postable
// (then the whole program was read). Throws as post_program's reading does.
std::optional<ToolSection> first_postable_section(std::string_view text,
                                                  const std::string& file_name,
                                                  const machines::MachineProfile& profile,
                                                  const PostSettings& settings);

// Without a model (PostSettings::normals_from_path): read ahead of the job
// for PostSettings::path_normals, and for a report, whose top views span
// the path. Throws as post_program's reading does.
PathNormalsAhead read_path_normals(std::string_view text, const std::string& file_name,
                                   const machines::MachineProfile& profile,
                                   const PostSettings& settings);

// Thrown for input the job cannot post soundly (the message says where and
// why); readers' own errors (GcodeError, ClError, TimingError, OutputError)
// pass through unchanged.
class PostError : public vcpost::Error {
 public:
  using vcpost::Error::Error;
};

// Posts `text` (the whole program; `file_name` for messages). Writes the
// output program to `sink` in pieces (nothing when `sink` is empty: a dry
// run): for G-code input the input with only S/F words changed; for CL
// input G-code in the profile's format. `points` receives every evaluated
// point in path order, once its block's plan is final.
//
// The job streams: it reads, evaluates, plans and writes through bounded
// windows (memory does not grow with the program, but for the text the
// caller holds), and calls `consumed(offset)` when it will not read the
// text before `offset` again, so the caller may release it. Contact and
// engagement run on `settings.threads` threads, chunk by chunk; the result
// does not depend on the number of threads. Callbacks are called from one
// thread at a time, not always the caller's.
PostSummary post_program(std::string_view text, const std::string& file_name,
                         const geometry::SurfaceModel& model,
                         const machines::MachineProfile& profile, const PostSettings& settings,
                         const std::function<void(std::string_view)>& sink,
                         const Progress& progress = {}, const PointSink& points = {},
                         const std::function<void(std::uint64_t)>& consumed = {});

}  // namespace vcpost::post
