#include "vcpost/post.h"

#include <array>
#include <charconv>
#include <string>

#include "api/translate.h"
#include "postproc/cli/job_runner.h"
#include "postproc/cli/model_loader.h"
#include "postproc/cli/post_options.h"
#include "postproc/output/gcode_writer.h"
#include "postproc/post/acceptance.h"
#include "postproc/post/post_job.h"

namespace vcpost::api {

struct Model::Loaded {
  cli::LoadedModel model;
};

Model::Model(std::shared_ptr<const Loaded> loaded) : loaded_(std::move(loaded)) {}

Model Model::load(const std::string& path) {
  return guarded(
      [&] { return Model(std::make_shared<const Loaded>(Loaded{cli::load_model(path)})); });
}

std::string Model::kind() const { return loaded_->model.kind; }
std::string Model::description() const { return loaded_->model.description; }

const geometry::SurfaceModel& internal(const Model& model) { return *model.loaded_->model.model; }

namespace {

// The options as `vcpost post` holds them, so the library and the command
// set the job up by the same rules (cli::settings_from).
cli::PostArguments arguments_from(const PostOptions& options) {
  auto positive = [](double value, const char* option) {
    if (!(value > 0)) throw Error(std::string(option) + ": must be positive", {}, option);
  };
  positive(options.vc, "--vc");
  positive(options.ap, "--ap");
  positive(options.spacing_mm, "--spacing");
  positive(options.contact_tolerance_mm, "--contact-tolerance");
  if (options.ae) positive(*options.ae, "--ae");
  if (options.fz_mm) positive(*options.fz_mm, "--fz");
  if (options.teeth) positive(*options.teeth, "--teeth");
  cli::PostArguments args;
  if (!options.tool.empty()) args.tools = {options.tool};
  std::array<char, 32> vc{};  // shortest text that reads back as the same double
  args.vc = {std::string(vc.data(), std::to_chars(vc.begin(), vc.end(), options.vc).ptr)};
  args.ap = options.ap;
  args.ae = options.ae;
  args.ae_override = options.ae_override;
  args.policy = options.policy == DiameterPolicy::tangent ? "tangent"
                : options.policy == DiameterPolicy::mean  ? "mean"
                                                          : "max";
  args.cl_point = options.cl_point == ClPoint::center ? "center" : "tip";
  args.spacing = options.spacing_mm;
  args.tolerance = options.contact_tolerance_mm;
  args.dialect = options.dialect;
  args.adjust_feed = options.adjust_feed;
  args.fz = options.fz_mm;
  args.teeth = options.teeth;
  args.threads = options.threads;
  args.stock_from_program = options.stock_from_program;
  if (options.stock_box) {
    for (std::size_t i = 0; i < options.stock_box->size(); ++i) {
      std::array<char, 32> number{};
      const double v = (*options.stock_box)[i];
      args.stock_box +=
          (i > 0 ? "," : "") +
          std::string(number.data(), std::to_chars(number.begin(), number.end(), v).ptr);
    }
  }
  args.stock_model = options.stock_model;
  args.stock_cell = options.stock_cell_mm;
  positive(options.stock_memory_mb, "--stock-memory");
  args.stock_memory_mb = options.stock_memory_mb;
  return args;
}

Vec3 vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

std::optional<VcStatistics> statistics(const std::optional<post::VcStatistics>& s) {
  if (!s) return std::nullopt;
  return VcStatistics{s->min, s->max, s->mean, s->within_5_percent, s->within_10_percent};
}

PostSummary summary_from(const post::PostSummary& s) {
  PostSummary out;
  out.kind = std::string(post::to_string(s.kind));
  out.blocks = s.blocks;
  out.motion_events = s.motion_events;
  out.points = s.samples;
  out.touching = s.touching;
  out.lifted = s.lifted;
  out.gouging = s.gouging;
  out.missed = s.missed;
  out.ae_measured = s.ae_measured;
  out.ae_given = s.ae_given;
  out.ae_first_pass = s.ae_first_pass;
  out.program_time_s = s.program_time_s;
  out.cutting_time_s = s.cutting_time_s;
  out.s_words = s.s_words;
  out.f_words = s.f_words;
  out.vc_before = statistics(s.before);
  out.vc_after = statistics(s.after);
  if (const auto& k = s.stock) {
    out.stock = StockSummary{k->source,
                             k->cell_mm,
                             k->nx,
                             k->ny,
                             k->memory_bytes,
                             k->warnings,
                             k->points_stock,
                             k->points_clamped,
                             k->points_air,
                             k->points_given,
                             k->band_time_s,
                             k->over_nominal_points,
                             k->over_nominal_time_s,
                             k->ap_max_mm};
  }
  return out;
}

}  // namespace

PostResult post(std::string_view program, const std::string& program_name, const Model& model,
                const MachineProfile& profile, const PostOptions& options) {
  return guarded(
      [&] {
        const cli::PostArguments args = arguments_from(options);
        post::PostSettings settings = cli::settings_from(args);
        if (settings.stock) cli::load_stock_model(args, *settings.stock);
        PostResult result;
        const auto sink = [&](std::string_view bytes) { result.program.append(bytes); };
        post::PointSink points;
        if (options.keep_points) {
          points = [&](const pipeline::PathSample& sample, const pipeline::PointResult& point,
                       const post::PointRecord& record) {
            PostPoint p;
            p.line = record.line;
            p.time_s = record.time_s;
            p.point = vec(sample.point);
            p.touching = point.contact.status == geometry::BallStatus::touching;
            if (point.contact.contact) p.contact = vec(point.contact.contact->point);
            p.normal = vec(point.contact.normal);
            p.d_ref = point.d_ref;
            if (point.engagement || point.ap_source == pipeline::ApSource::air) p.ap = point.ap;
            p.ap_from_stock = point.ap_source != pipeline::ApSource::given;
            p.s_before = record.s_before;
            p.s_after = record.s_after;
            result.points.push_back(p);
          };
        }
        const post::PostSummary summary = post::post_program(
            program, program_name, internal(model), internal(profile), settings, sink, {}, points);
        cli::require_accepted(post::judge_posted(summary, program_name));
        result.summary = summary_from(summary);
        return result;
      },
      program_name);
}

}  // namespace vcpost::api
