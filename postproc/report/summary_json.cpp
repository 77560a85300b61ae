// The JSON summary; its keys are documented in postproc/report/README.md
// and are stable: new keys may be added, none renamed or removed.
#include "postproc/report/report.h"

namespace vcpost::report {
namespace {

using nlohmann::json;

json optional_number(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

json distribution_json(const std::optional<Distribution>& d) {
  if (!d) return nullptr;
  return {{"min", d->min},
          {"max", d->max},
          {"mean", d->mean},
          {"p5", d->p5},
          {"p50", d->p50},
          {"p95", d->p95},
          {"resolution", d->resolution}};
}

json speed_json(const SpeedStatistics& s) {
  const json vc = distribution_json(s.vc);
  return {{"vc", vc},
          {"within_5_percent", s.within_5_percent},
          {"within_10_percent", s.within_10_percent},
          {"time_s",
           {{"below_nominal", s.below_nominal_time_s},
            {"above_nominal", s.above_nominal_time_s},
            {"clamped_n_max", s.clamped_max_time_s},
            {"clamped_n_min", s.clamped_min_time_s},
            {"slew", optional_number(s.slew_time_s)}}}};
}

}  // namespace

json summary_json(const ReportData& data) {
  const ReportInputs& in = data.inputs;
  const ReportStatistics& st = data.statistics;
  const post::PostSummary& job = data.summary;
  return {
      {"schema", "vcpost-report/1"},
      {"inputs",
       {{"program", in.program},
        {"kind", in.program_kind},
        {"model",
         {{"file", in.model}, {"kind", in.model_kind}, {"description", in.model_description}}},
        {"tool", in.tool},
        {"ap", in.ap_mm},
        {"ae", optional_number(in.ae_mm)},
        {"ae_override", in.ae_override},
        {"policy", in.policy},
        {"cl_point", in.cl_point},
        {"spacing", in.spacing_mm},
        {"adjust_feed", in.adjust_feed}}},
      {"profile", {{"name", in.machine}, {"n_min_rpm", in.n_min_rpm}, {"n_max_rpm", in.n_max_rpm}}},
      {"vc_nominal", in.vc_nominal},
      {"points",
       {{"total", st.points},
        {"cutting", st.cutting_points},
        {"touching", st.touching},
        {"no_contact", st.lifted + st.missed},
        {"lifted", st.lifted},
        {"missed", st.missed},
        {"gouge", st.gouging},
        {"no_cut", st.no_cut},
        {"ae_measured", job.ae_measured},
        {"ae_given", job.ae_given},
        {"ae_first_pass", job.ae_first_pass}}},
      {"blocks", job.blocks},
      {"time_s", {{"program", job.program_time_s}, {"cutting", job.cutting_time_s}}},
      {"before", speed_json(st.before)},
      {"after", speed_json(st.after)},
      {"words_written", {{"s", job.s_words}, {"f", job.f_words}}},
      {"surface",
       {{"points", st.surface_points},
        {"cusp_um", distribution_json(st.cusp_um)},
        {"ra_um", distribution_json(st.ra_um)},
        {"rz_um", distribution_json(st.rz_um)}}},
      {"run_time_s", data.run_time_s},
  };
}

}  // namespace vcpost::report
