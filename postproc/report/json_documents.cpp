// The one writer of vcpost's JSON vocabulary (docs/json.md): every key is
// spelt here once, and both documents are built from these pieces.
#include "postproc/report/json_documents.h"

#include "postproc/report/report.h"

namespace vcpost::report {
namespace {

using nlohmann::json;

json optional_number(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

// {min, max, mean, p5, p50, p95, resolution}, or null.
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

// A side (before/after) from the job's own statistics: {vc {min, max,
// mean}, within_5_percent, within_10_percent}, all null when nothing cut.
json speed_json(const std::optional<post::VcStatistics>& s) {
  if (!s) return {{"vc", nullptr}, {"within_5_percent", nullptr}, {"within_10_percent", nullptr}};
  return {{"vc", {{"min", s->min}, {"max", s->max}, {"mean", s->mean}}},
          {"within_5_percent", s->within_5_percent},
          {"within_10_percent", s->within_10_percent}};
}

// A side from the report's statistics: the same keys with percentiles and
// the time the limits bind.
json speed_json(const SpeedStatistics& s) {
  return {{"vc", distribution_json(s.vc)},
          {"within_5_percent", s.within_5_percent},
          {"within_10_percent", s.within_10_percent},
          {"time_s",
           {{"below_nominal", s.below_nominal_time_s},
            {"above_nominal", s.above_nominal_time_s},
            {"clamped_n_max", s.clamped_max_time_s},
            {"clamped_n_min", s.clamped_min_time_s},
            {"slew", optional_number(s.slew_time_s)}}}};
}

// The contact tally of a set of points.
json points_json(std::uint64_t total, const post::ContactCounts& c) {
  return {{"total", total},
          {"touching", c.touching},
          {"lifted", c.lifted},
          {"missed", c.missed},
          {"gouging", c.gouging}};
}

// ... with where each point's ae came from.
json points_json(std::uint64_t total, const post::ContactCounts& c, const post::PostSummary& job) {
  json out = points_json(total, c);
  out["ae_measured"] = job.ae_measured;
  out["ae_given"] = job.ae_given;
  out["ae_first_pass"] = job.ae_first_pass;
  return out;
}

json inputs_json(const ReportInputs& in, bool tool_known) {
  return {{"program", in.program},
          {"kind", in.program_kind},
          {"model",
           {{"file", in.model}, {"kind", in.model_kind}, {"description", in.model_description}}},
          {"tool", tool_known ? json(in.tool) : json(nullptr)},
          {"ap", in.ap_mm},
          {"ae", optional_number(in.ae_mm)},
          {"ae_override", in.ae_override},
          {"policy", in.policy},
          {"cl_point", in.cl_point},
          {"spacing", in.spacing_mm},
          {"adjust_feed", in.adjust_feed}};
}

json profile_json(const ReportInputs& in) {
  return {{"name", in.machine}, {"n_min_rpm", in.n_min_rpm}, {"n_max_rpm", in.n_max_rpm}};
}

json time_json(const post::PostSummary& job) {
  return {{"program", job.program_time_s}, {"cutting", job.cutting_time_s}};
}

json words_json(std::uint64_t s, std::uint64_t f) { return {{"s", s}, {"f", f}}; }

json words_json(const post::PostSummary& job) {
  json out = words_json(job.s_words, job.f_words);
  out["repeated_lines"] = job.repeated_lines;
  return out;
}

json depth_json(const post::DepthStatistics& d) {
  if (d.points == 0) return nullptr;
  return {{"points", d.points}, {"min", d.min}, {"median", d.median}, {"max", d.max}};
}

json tool_json(const std::optional<tools::ToolEntry>& entry) {
  if (!entry) return nullptr;
  const tools::ToolEntry& e = *entry;
  return {{"shape", tools::to_string(e.shape)},
          {"diameter", e.diameter},
          {"corner_radius", e.corner_radius ? json(*e.corner_radius) : nullptr},
          {"name", e.name},
          {"source", tools::to_string(e.origin)},
          {"where", e.where}};
}

json offset_json(const std::optional<post::OffsetDiagnosis>& offset) {
  if (!offset) return nullptr;
  return {{"offset", offset->offset_mm}, {"share", offset->share}, {"causes", offset->causes}};
}

json section_json(const post::ToolSection& section) {
  return {{"tool_number", section.tool ? json(*section.tool) : nullptr},
          {"tool", tool_json(section.entry)},
          {"first_line", section.first_line},
          {"posted", section.posted},
          {"reason", section.reason},
          {"vc_nominal", section.posted ? json(section.vc_nominal) : nullptr},
          {"stock_mm", {{"radial", section.stock.radial}, {"axial", section.stock.axial}}},
          {"time_s", {{"start", section.start_s}, {"end", section.end_s}}},
          {"points", points_json(section.points, section)},
          {"gouge_depth", depth_json(section.gouge)},
          {"lift_height", depth_json(section.lift)},
          {"offset", offset_json(section.offset)},
          {"words_written", words_json(section.s_words, section.f_words)},
          {"before", speed_json(section.before)},
          {"after", speed_json(section.after)}};
}

json sections_json(const post::PostSummary& job) {
  json out = json::array();
  for (const post::ToolSection& section : job.sections) out.push_back(section_json(section));
  return out;
}

json within_10(const std::optional<post::VcStatistics>& v) {
  return v ? json(v->within_10_percent) : json(nullptr);
}

json s_placement_json(const post::SPlacement& p) {
  json sections = json::array();
  for (const auto& s : p.sections) {
    sections.push_back({{"start_s", s.start_s},
                        {"cutting_s", s.cutting_time_s},
                        {"s_words", s.s_words},
                        {"in_feed", s.in_feed},
                        {"stops", s.stops},
                        {"time_cost_s", s.time_cost_s},
                        {"within_10_percent_before", within_10(s.before)},
                        {"within_10_percent_after", within_10(s.after)}});
  }
  return {{"mode", !p.at_stops ? "inline"
                   : p.priced  ? "priced"
                               : "at_stops"},
          {"s_words", p.s_words},
          {"in_feed", p.in_feed},
          {"stops", p.stops},
          {"stop_cost_s", p.stop_cost_s},
          {"time_cost_s", p.time_cost_s},
          {"sections", sections}};
}

json marks_json(const ReportData& data) {
  json out = json::array();
  for (const SectionMark& mark : data.section_marks) {
    std::string label = "section " + std::to_string(mark.section);
    for (const post::ToolSection& s : data.summary.sections) {
      if (s.index != mark.section) continue;
      label = s.tool ? "T" + std::to_string(*s.tool) : std::string("first tool");
      if (s.entry) label += " " + std::string(tools::to_string(s.entry->shape));
      label += s.posted ? " (posted)" : " (kept)";
    }
    out.push_back(
        {{"section", mark.section}, {"cutting_time_s", mark.cut_time_s}, {"label", label}});
  }
  return out;
}

// Posted without a model: how each point's normal was found (path_normals.h).
void add_normals(json& out, const post::PostSummary& job) {
  if (const auto& n = job.path_normals) {
    out["normals"] = {{"source", "toolpath"},
                      {"two_sided", n->two_sided},
                      {"one_sided", n->one_sided},
                      {"kept", n->kept}};
  }
}

// The in-process stock and the ap it gave (docs/stock.md).
json stock_json(const post::StockSummary& s) {
  const auto& b = s.box;
  return {
      {"source", s.source},
      {"box_mm", {b.min().x(), b.min().y(), b.min().z(), b.max().x(), b.max().y(), b.max().z()}},
      {"cell_mm", s.cell_mm},
      {"cells", {s.nx, s.ny}},
      {"cell_note", s.cell_note},
      {"memory_bytes", s.memory_bytes},
      {"copies", s.copies},
      {"sections_swept", s.swept},
      {"warnings", s.warnings},
      {"build_s", s.build_s},
      {"ap_nominal_mm", s.nominal_ap_mm},
      {"points",
       {{"stock", s.points_stock},
        {"clamped", s.points_clamped},
        {"air", s.points_air},
        {"given", s.points_given},
        {"over_nominal", s.over_nominal_points}}},
      {"time_s",
       {{"stock", s.stock_time_s},
        {"air", s.air_time_s},
        {"over_nominal", s.over_nominal_time_s},
        {"ap_bands",
         {{"upto_1x", s.band_time_s[0]},
          {"upto_1_5x", s.band_time_s[1]},
          {"upto_2x", s.band_time_s[2]},
          {"over_2x", s.band_time_s[3]}}}}},
      {"ap_max_mm", s.ap_max_mm}};
}

// The keys both documents carry.
json common_json(const char* schema, const ReportInputs& in, bool tool_known, json vc_nominal,
                 const post::PostSummary& job, double run_time_s) {
  return {{"schema", schema},
          {"inputs", inputs_json(in, tool_known)},
          {"profile", profile_json(in)},
          {"vc_nominal", std::move(vc_nominal)},
          {"blocks", job.blocks},
          {"time_s", time_json(job)},
          {"words_written", words_json(job)},
          {"s_placement", s_placement_json(job.s_placement)},
          {"sections", sections_json(job)},
          {"tool_notes", job.tool_notes},
          {"run_time_s", run_time_s}};
}

}  // namespace

json report_json(const ReportData& data) {
  const ReportStatistics& st = data.statistics;
  const post::PostSummary& job = data.summary;
  json out =
      common_json(kReportSchema, data.inputs, true, data.inputs.vc_nominal, job, data.run_time_s);
  json points = points_json(st.points, st, job);
  points["cutting"] = st.cutting_points;
  points["no_contact"] = st.lifted + st.missed;
  points["no_cut"] = st.no_cut;
  out["points"] = std::move(points);
  out["before"] = speed_json(st.before);
  out["after"] = speed_json(st.after);
  out["surface"] = {{"points", st.surface_points},
                    {"cusp_um", distribution_json(st.cusp_um)},
                    {"ra_um", distribution_json(st.ra_um)},
                    {"rz_um", distribution_json(st.rz_um)}};
  out["section_marks"] = marks_json(data);
  add_normals(out, job);
  if (job.stock) out["stock"] = stock_json(*job.stock);
  return out;
}

json post_summary_json(const ReportInputs& inputs, bool tool_posted,
                       const post::PostSummary& summary, double run_time_s) {
  json out =
      common_json(kSummarySchema, inputs, tool_posted,
                  tool_posted ? json(inputs.vc_nominal) : json(nullptr), summary, run_time_s);
  out["motion_events"] = summary.motion_events;
  out["points"] = points_json(summary.samples, summary, summary);
  out["before"] = speed_json(summary.before);
  json after = speed_json(summary.after);
  after["time_s"] = {{"clamped_n_max", summary.time_clamped_max_s},
                     {"clamped_n_min", summary.time_clamped_min_s},
                     {"slew", summary.time_slew_s},
                     {"rate", summary.time_rate_s}};
  out["after"] = std::move(after);
  add_normals(out, summary);
  if (summary.stock) out["stock"] = stock_json(*summary.stock);
  return out;
}

}  // namespace vcpost::report
