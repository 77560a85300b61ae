// The HTML page: one file, no external resources. Layout and drawing code
// are ours (page/report.html, .css, .js, embedded at build time); the
// charts are Chart.js 3 (inlined from the installed copy).
// The data sit in a JSON script element; the page checks itself after
// drawing (canvases with ink, script errors) into #selfcheck, which the
// browser test reads.
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "core/text.h"
#include "postproc/report/page_assets.h"
#include "postproc/report/report.h"

namespace vcpost::report {
namespace {

using nlohmann::json;

// Rounded so the page stays small: nlohmann prints the shortest repr.
double round_to(double value, double step) { return std::round(value / step) * step; }

json flat_points(const std::vector<PlotPoint>& points, double x_step, double y_step) {
  json out = json::array();
  for (const auto& p : points) {
    out.push_back(round_to(p.x, x_step));
    out.push_back(round_to(p.y, y_step));
  }
  return out;
}

// The plan grids, sparse: the occupied cells (any grid) as gaps between
// their row-major indices, and each grid's values there (null where empty).
json sparse_grids(const PlanGrid& before, const PlanGrid& after, const PlanGrid& cusp,
                  const PlanGrid& ap, bool with_ap) {
  json index_gaps = json::array(), b = json::array(), a = json::array(), c = json::array(),
       p = json::array();
  auto value = [](const std::optional<float>& v, double scale, double step) {
    return v ? json(round_to(scale * static_cast<double>(*v), step)) : json(nullptr);
  };
  std::size_t last = 0;
  for (std::size_t i = 0; i < after.cells().size(); ++i) {
    if (!before.cells()[i] && !after.cells()[i] && !cusp.cells()[i] && !ap.cells()[i]) continue;
    index_gaps.push_back(i - last);
    last = i;
    b.push_back(value(before.cells()[i], 100, 0.01));
    a.push_back(value(after.cells()[i], 100, 0.01));
    c.push_back(value(cusp.cells()[i], 1, 0.01));
    p.push_back(value(ap.cells()[i], 1, 0.001));
  }
  json out = {{"nx", after.nx()},     {"ny", after.ny()},     {"cell", after.cell()},
              {"x0", after.lo().x()}, {"y0", after.lo().y()}, {"index_gaps", index_gaps},
              {"before_pct", b},      {"after_pct", a},       {"cusp_um", c}};
  if (with_ap) out["ap_mm"] = std::move(p);  // with an in-process stock only
  return out;
}

std::string_view bound_text(plan::Bound bound) {
  switch (bound) {
    case plan::Bound::none:
      return "target";
    case plan::Bound::resolution:
      return "S resolution";
    case plan::Bound::hysteresis:
      return "hysteresis";
    case plan::Bound::n_max:
      return "n_max";
    case plan::Bound::n_min:
      return "n_min";
    case plan::Bound::slew:
      return "slew limit";
    case plan::Bound::rate:
      return "S-word rate";
    case plan::Bound::stretch:
      return "one S per stretch between stops";
    case plan::Bound::program:
      return "program's S";
    case plan::Bound::rapid:
      return "rapid";
    case plan::Bound::off:
      return "spindle off";
  }
  return "?";
}

json regions_json(const std::vector<Region>& regions) {
  json out = json::array();
  for (const auto& r : regions) {
    out.push_back({{"first_line", r.first_line},
                   {"last_line", r.last_line},
                   {"start_s", round_to(r.start_cut_s, 1e-3)},
                   {"duration_s", round_to(r.duration_s, 1e-4)},
                   {"worst_pct", round_to(100 * r.worst_dev, 0.01)},
                   {"vc_min", round_to(r.vc_min, 0.01)},
                   {"vc_max", round_to(r.vc_max, 0.01)},
                   {"x", round_to(r.worst_xy.x(), 0.01)},
                   {"y", round_to(r.worst_xy.y(), 0.01)},
                   {"bound", bound_text(r.bound)}});
  }
  return out;
}

json page_data(const ReportData& d) {
  const double vc = d.inputs.vc_nominal;
  double total = 0;
  for (const auto& p : d.vc_after) total = std::max(total, p.x);
  const double t_step = total > 1000 ? 0.01 : 1e-4;
  return {
      {"summary", report_json(d)},
      {"bucket_points", d.plot_bucket_points},
      {"vc",
       {{"before", flat_points(d.vc_before, t_step, vc * 1e-5)},
        {"after", flat_points(d.vc_after, t_step, vc * 1e-5)}}},
      {"s",
       {{"before", flat_points(d.s_before, t_step, 0.1)},
        {"after", flat_points(d.s_after, t_step, 0.1)}}},
      {"hist",
       {{"step_pct", 100 * d.histogram.step},
        {"limit_pct", 100 * d.histogram.limit},
        {"before_s", d.histogram.before_s},
        {"after_s", d.histogram.after_s}}},
      {"grid", sparse_grids(d.dev_before, d.dev_after, d.cusp, d.ap, d.summary.stock.has_value())},
      {"regions",
       {{"after", regions_json(d.regions_after)},
        {"before", regions_json(d.regions_before)},
        {"after_threshold_pct", 100 * kRegionThresholdAfter},
        {"before_threshold_pct", 100 * kRegionThresholdBefore}}},
  };
}

// JSON inside a <script> element: '<' only occurs inside strings there,
// and written as \u003c it can never close the element.
std::string script_safe(const std::string& json_text) {
  std::string out;
  out.reserve(json_text.size());
  for (const char c : json_text) {
    if (c == '<') {
      out += "\\u003c";
    } else {
      out += c;
    }
  }
  return out;
}

std::string html_escape(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// The page with its slots filled: each of `slots`' names must follow the
// one before in the template (page_assets.h); the texts are not searched.
std::string fill_slots(std::string_view page,
                       std::initializer_list<std::pair<std::string_view, std::string_view>> slots) {
  std::size_t size = page.size();
  for (const auto& slot : slots) size += slot.second.size();
  std::string out;
  out.reserve(size);
  for (const auto& [name, text] : slots) {
    const std::size_t at = page.find(name);
    if (at == std::string_view::npos) {
      throw std::logic_error("the report's page has no slot " + std::string(name));
    }
    out += page.substr(0, at);
    out += text;
    page.remove_prefix(at + name.size());
  }
  out += page;
  return out;
}

}  // namespace

std::string render_html(const ReportData& data, std::string_view chart_library) {
  const std::string lower = to_lower(chart_library);
  if (lower.find("</script") != std::string::npos) {
    // Reaches the user through post_options.cpp, which turns it into
    // vcpost::Error E2004 ("HTML report: ...").
    throw std::invalid_argument("the charting library contains '</script' and cannot be inlined");
  }
  const std::string data_text = script_safe(page_data(data).dump());
  const std::string title = html_escape("vcpost report: " + data.inputs.program);
  return fill_slots(assets::page_html, {{"@TITLE@", title},
                                        {"@STYLE@", assets::page_css},
                                        {"@DATA@", data_text},
                                        {"@CHART_JS@", chart_library},
                                        {"@SCRIPT@", assets::page_js}});
}

}  // namespace vcpost::report
