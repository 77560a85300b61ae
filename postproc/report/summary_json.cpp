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

json depth_json(const post::DepthStatistics& d) {
  if (d.points == 0) return nullptr;
  return {{"points", d.points}, {"min", d.min}, {"median", d.median}, {"max", d.max}};
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

json within_10(const std::optional<post::VcStatistics>& v) {
  return v ? json(v->within_10_percent) : json(nullptr);
}

}  // namespace

json vc_json(const std::optional<post::VcStatistics>& s) {
  if (!s) return nullptr;
  return {{"min", s->min},
          {"max", s->max},
          {"mean", s->mean},
          {"within_5_percent", s->within_5_percent},
          {"within_10_percent", s->within_10_percent}};
}

json tool_sections_json(const post::PostSummary& s) {
  json out = json::array();
  for (const post::ToolSection& section : s.sections) {
    json tool = nullptr;
    if (section.entry) {
      const tools::ToolEntry& e = *section.entry;
      tool = {{"shape", tools::to_string(e.shape)},
              {"diameter", e.diameter},
              {"corner_radius", e.corner_radius ? json(*e.corner_radius) : nullptr},
              {"name", e.name},
              {"source", tools::to_string(e.origin)},
              {"where", e.where}};
    }
    json offset = nullptr;
    if (section.offset) {
      offset = {{"offset", section.offset->offset_mm},
                {"share", section.offset->share},
                {"causes", section.offset->causes}};
    }
    out.push_back({{"tool_number", section.tool ? json(*section.tool) : nullptr},
                   {"tool", tool},
                   {"first_line", section.first_line},
                   {"posted", section.posted},
                   {"reason", section.reason},
                   {"vc_nominal", section.posted ? json(section.vc_nominal) : nullptr},
                   {"time_s", {{"start", section.start_s}, {"end", section.end_s}}},
                   {"points", section.points},
                   {"contact",
                    {{"touching", section.touching},
                     {"lifted", section.lifted},
                     {"gouging", section.gouging},
                     {"missed", section.missed}}},
                   {"gouge_depth", depth_json(section.gouge)},
                   {"lift_height", depth_json(section.lift)},
                   {"offset", offset},
                   {"words_written", {{"s", section.s_words}, {"f", section.f_words}}},
                   {"vc_before", vc_json(section.before)},
                   {"vc_after", vc_json(section.after)}});
  }
  return out;
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
  return {{"mode", p.at_stops ? "at_stops" : "inline"},
          {"s_words", p.s_words},
          {"in_feed", p.in_feed},
          {"stops", p.stops},
          {"stop_cost_s", p.stop_cost_s},
          {"time_cost_s", p.time_cost_s},
          {"sections", sections}};
}

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
      {"s_placement", s_placement_json(job.s_placement)},
      {"surface",
       {{"points", st.surface_points},
        {"cusp_um", distribution_json(st.cusp_um)},
        {"ra_um", distribution_json(st.ra_um)},
        {"rz_um", distribution_json(st.rz_um)}}},
      {"sections", tool_sections_json(job)},
      {"section_marks", marks_json(data)},
      {"tool_notes", job.tool_notes},
      {"run_time_s", data.run_time_s},
  };
}

}  // namespace vcpost::report
