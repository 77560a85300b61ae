#include "postproc/post/stock_timeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "geometry/stock/height_field.h"
#include "geometry/tool_contact.h"
#include "postproc/post/path_reader.h"
#include "postproc/post/stock_source.h"

namespace vcpost::post {
namespace {

using geometry::stock::Cutter;
using geometry::stock::HeightField;

// The default cell: this share of the smallest evaluated tool's diameter,
// within [kMinCell, kMaxCell] mm.
constexpr double kCellPerDiameter = 1.0 / 50;
constexpr double kMinCell = 0.05, kMaxCell = 1.0;
// Tips swept in one call: the path is cut in pieces this long, so memory
// stays flat with the program's length.
constexpr std::size_t kTipsPerCut = 1 << 15;

class FieldDepth final : public pipeline::MaterialDepth {
 public:
  explicit FieldDepth(std::shared_ptr<const HeightField> field) : field_(std::move(field)) {}
  double depth_along(const Eigen::Vector3d& p, const Eigen::Vector3d& n,
                     double max_mm) const override {
    return field_->depth_along(p, n, max_mm);
  }

 private:
  std::shared_ptr<const HeightField> field_;
};

// What the first read learns: each section, and whether any of its points
// lie in a tilted frame.
struct SectionPlan {
  std::optional<ToolSection> section;
  bool tilted = false;
};

std::string named(const ToolSection& s) {
  std::string name = "section " + std::to_string(s.index);
  if (s.tool) name += " (T" + std::to_string(*s.tool) + ")";
  return name;
}

// The shape that removes material in a section; empty where its tool's
// shape is unknown.
std::optional<Cutter> cutter_of(const ToolSection& s) {
  if (!s.entry) return std::nullopt;
  if (s.entry->shape == tools::ToolShape::drill) {
    if (!(s.entry->diameter > 0)) return std::nullopt;
    return Cutter::drill(s.entry->diameter);
  }
  const auto tool = s.entry->geometry();
  if (!tool) return std::nullopt;
  return Cutter{*tool, 0};
}

std::string decimal_text(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// The program and what both reads take with it.
struct ProgramInput {
  std::string_view text;
  const std::string& file_name;
  ProgramKind kind;
  const gcode::Dialect& dialect;
  const machines::MachineProfile& profile;
  const PostSettings& settings;
  const tools::ToolChoices& choices;
};

// Reads the whole program with samples `spacing_mm` apart, handing each
// chunk to `on_chunk`; returns Klartext's BLK FORM, if it declared one.
template <class OnChunk>
std::optional<heidenhain::StockBox> read_program(const ProgramInput& in, double spacing_mm,
                                                 OnChunk&& on_chunk) {
  PathReader reader(in.text, in.file_name, in.kind, in.dialect, in.profile, spacing_mm, false,
                    in.choices, in.settings.point.ap);
  reader.set_program_loader(in.settings.program_loader);
  Chunk chunk;
  while (reader.read(chunk, chunk_samples)) on_chunk(chunk);
  return reader.klartext_stock();
}

struct ProgramPlan {
  std::vector<SectionPlan> sections;  // by ToolSection::index
  std::optional<heidenhain::StockBox> blk_form;
};

// First read: the sections, their tools, the frames they work in (and
// Klartext's BLK FORM). Samples only at the moves' ends.
ProgramPlan read_plan(const ProgramInput& in) {
  ProgramPlan plan;
  std::vector<SectionPlan>& plans = plan.sections;
  plan.blk_form = read_program(in, 1e6, [&](Chunk& chunk) {
    for (ToolSection& s : chunk.sections) {
      if (plans.size() <= s.index) plans.resize(s.index + 1);
      plans[s.index].section = std::move(s);
    }
    for (const Slot& slot : chunk.slots) {
      if ((slot.kind == SlotKind::sample || slot.kind == SlotKind::kept) &&
          slot.sample.frame != nullptr) {
        if (plans.size() <= slot.section) plans.resize(slot.section + 1);
        plans[slot.section].tilted = true;
      }
    }
  });
  return plan;
}

// Where the stock starts; names where it comes from in `summary`.
Eigen::AlignedBox3d stock_extent(const ProgramInput& in,
                                 const std::optional<heidenhain::StockBox>& blk_form,
                                 StockSummary& summary) {
  const StockSettings& stock = *in.settings.stock;
  if (stock.from_program) {
    std::optional<DeclaredStock> declared;
    if (in.kind == ProgramKind::cldata) {
      declared = cl_declared_stock(in.text, in.file_name);
    } else if (in.kind == ProgramKind::heidenhain && blk_form) {
      declared = klartext_declared_stock(
          blk_form->min, blk_form->max, in.file_name + ":" + std::to_string(blk_form->source.line));
    }
    if (!declared)
      throw vcpost::Error(Code::E4720,
                          in.file_name +
                              ": the program declares no stock (Klartext BLK FORM, APT CL "
                              "INSERT/Stock Size): give --stock-box or --stock-model");
    summary.source = declared->words + " at " + declared->where;
    return declared->box;
  }
  if (stock.box) {
    summary.source = "--stock-box";
    return *stock.box;
  }
  Eigen::AlignedBox3d extent;
  for (const Eigen::Vector3f& c : *stock.triangles) extent.extend(c.cast<double>());
  summary.source = "--stock-model " + stock.model_name;
  return extent;
}

// The sections the job evaluates, as far as the stock's cell and copies
// depend on them.
struct EvaluatedSections {
  std::uint32_t count = 0;
  std::uint32_t last = 0;  // no section after it needs the stock
  double smallest_diameter = 0;
};

EvaluatedSections evaluated_sections(const std::vector<SectionPlan>& plans) {
  EvaluatedSections evaluated;
  for (const SectionPlan& p : plans) {
    if (!p.section || !p.section->postable) continue;
    ++evaluated.count;
    evaluated.last = p.section->index;
    const double d = p.section->entry->diameter;
    evaluated.smallest_diameter =
        evaluated.smallest_diameter > 0 ? std::min(evaluated.smallest_diameter, d) : d;
  }
  return evaluated;
}

// The cell: given, or from the smallest evaluated tool, coarsened to fit
// the memory the field and its copies may take; says which in `summary`.
double stock_cell(const StockSettings& stock, const Eigen::AlignedBox3d& extent,
                  const EvaluatedSections& evaluated, StockSummary& summary) {
  auto need = [&](double cell) {
    const double nx = std::ceil(extent.sizes().x() / cell),
                 ny = std::ceil(extent.sizes().y() / cell);
    return (1.0 + evaluated.count) * nx * ny * sizeof(float);
  };
  const auto limit = static_cast<double>(stock.memory_limit);
  if (stock.cell_mm) {
    const double cell = *stock.cell_mm;
    summary.cell_note = "--stock-cell";
    if (need(cell) > limit)
      throw vcpost::Error(
          Code::E4724, "the stock at --stock-cell " + decimal_text(cell) + " mm needs " +
                           decimal_text(std::ceil(need(cell) / (1 << 20))) + " MB (the field and " +
                           std::to_string(evaluated.count) +
                           " copies, one per evaluated section), above " + "--stock-memory " +
                           std::to_string(stock.memory_limit >> 20) +
                           " MB: give a coarser cell or more memory");
    return cell;
  }
  const double smallest = evaluated.smallest_diameter;
  double cell =
      std::clamp(smallest > 0 ? smallest * kCellPerDiameter : kMaxCell, kMinCell, kMaxCell);
  summary.cell_note = "the smallest evaluated tool's D/50 within [0.05, 1] mm";
  if (need(cell) > limit) {
    const double fine = cell;
    while (need(cell) > limit) cell *= 1.05;
    cell = std::ceil(cell * 1000) / 1000;
    summary.cell_note = "coarsened from " + decimal_text(fine) + " mm to fit --stock-memory " +
                        std::to_string(stock.memory_limit >> 20) + " MB";
  }
  return cell;
}

// The stock before the program: the stock model's top, or a block over
// the extent. The engine's own memory check is per field; stock_cell
// counts the copies.
HeightField initial_field(const StockSettings& stock, const Eigen::AlignedBox3d& extent,
                          double cell) {
  return stock.triangles && !stock.from_program && !stock.box
             ? HeightField::from_triangles(*stock.triangles, cell, stock.memory_limit)
             : HeightField::block(extent.min(), extent.max(), cell, stock.memory_limit);
}

// Second read: every section's moves swept out of the field, a copy kept
// at the start of each evaluated section. Takes the program's slots in
// order; finish() after the last.
class Sweep {
 public:
  Sweep(HeightField field, const std::vector<SectionPlan>& plans, std::uint32_t last_evaluated,
        geometry::ClPoint cl_point, StockSummary& summary,
        std::vector<std::shared_ptr<const pipeline::MaterialDepth>>& before)
      : field_(std::move(field)),
        plans_(plans),
        last_evaluated_(last_evaluated),
        cl_point_(cl_point),
        summary_(summary),
        before_(before),
        memory_(field_.memory_bytes()) {}

  void take(const Slot& slot) {
    if (slot.section != current_) open_section(slot.section);
    if (slot.kind == SlotKind::rapid || slot.break_pass) flush();
    if (slot.kind != SlotKind::sample && slot.kind != SlotKind::kept) return;
    if (!cutter_) {
      if (unknown_tool_) warn_unknown_tool(*plans_.at(slot.section).section);
      return;
    }
    if (slot.sample.frame != nullptr) {  // tilted: not swept (see W4731)
      flush();
      return;
    }
    add_tip(slot.sample.point);
  }

  // The field and its copies' bytes.
  std::uint64_t finish() {
    flush();
    if (current_ && swept_any_) summary_.swept.push_back(*current_);
    return memory_;
  }

 private:
  void flush() {
    if (cutter_ && !tips_.empty()) {
      field_.cut_path(*cutter_, tips_);
      cut_since_copy_ = true;
      swept_any_ = true;
    }
    tips_.clear();
  }

  void open_section(std::uint32_t index) {
    flush();
    if (current_ && swept_any_) summary_.swept.push_back(*current_);
    current_ = index;
    swept_any_ = false;
    cutter_.reset();
    unknown_tool_ = false;
    const SectionPlan& plan = plans_.at(index);
    const ToolSection& s = *plan.section;
    if (s.postable) keep_stock_before(index);
    if (plan.tilted) {
      summary_.warnings.push_back(
          std::string(to_string(Code::W4731)) + ": " + named(s) +
          " works in a tilted plane (3+2): its tilted moves are not swept (the stock is a "
          "height field along the machine's Z) and its tilted points take --ap");
    }
    if (index >= last_evaluated_) return;  // nothing evaluated after it: not swept
    cutter_ = cutter_of(s);
    unknown_tool_ = !cutter_;  // warned at its first cutting move, if it has one
  }

  // The stock as it stands, for the evaluated section `index`: sections
  // that cut nothing in between share one copy.
  void keep_stock_before(std::uint32_t index) {
    if (cut_since_copy_ || !last_copy_) {
      if (index == last_evaluated_) {  // nothing is swept after it: the field, not a copy
        last_copy_ = std::make_shared<const HeightField>(std::move(field_));
      } else {
        last_copy_ = std::make_shared<const HeightField>(field_);
        memory_ += last_copy_->memory_bytes();
        ++summary_.copies;
      }
      cut_since_copy_ = false;
    }
    before_[index] = std::make_shared<FieldDepth>(last_copy_);
  }

  void warn_unknown_tool(const ToolSection& s) {
    summary_.warnings.push_back(std::string(to_string(Code::W4730)) + ": " + named(s) +
                                ": its tool's shape is unknown (" +
                                (s.entry ? s.entry->describe() : std::string("no tool")) +
                                "): not swept, the stock keeps its material there");
    unknown_tool_ = false;
  }

  // The cutter's tip at the path point; swept in pieces of kTipsPerCut, the
  // last tip of one piece starting the next.
  void add_tip(const Eigen::Vector3d& point) {
    const geometry::Tool& tool = cutter_->tool;
    const Eigen::Vector3d origin = geometry::tool_origin(point, tool, cl_point_);
    tips_.push_back(origin - Eigen::Vector3d(0, 0, tool.corner_radius));
    if (tips_.size() >= kTipsPerCut) {
      const Eigen::Vector3d last = tips_.back();
      flush();
      tips_.push_back(last);
    }
  }

  HeightField field_;
  const std::vector<SectionPlan>& plans_;
  const std::uint32_t last_evaluated_;
  const geometry::ClPoint cl_point_;
  StockSummary& summary_;
  std::vector<std::shared_ptr<const pipeline::MaterialDepth>>& before_;
  std::shared_ptr<const HeightField> last_copy_;
  std::uint64_t memory_;
  bool cut_since_copy_ = true;
  std::vector<Eigen::Vector3d> tips_;
  std::optional<Cutter> cutter_;  // empty: the current section is not swept
  std::optional<std::uint32_t> current_;
  bool swept_any_ = false;
  bool unknown_tool_ = false;  // the current section's tool shape is unknown, not yet warned
};

}  // namespace

std::unique_ptr<StockTimeline> build_stock_timeline(std::string_view text,
                                                    const std::string& file_name, ProgramKind kind,
                                                    const gcode::Dialect& dialect,
                                                    const machines::MachineProfile& profile,
                                                    const PostSettings& settings,
                                                    const tools::ToolChoices& choices) {
  const auto started = std::chrono::steady_clock::now();
  const ProgramInput in{text, file_name, kind, dialect, profile, settings, choices};
  const StockSettings& stock = *settings.stock;
  auto timeline = std::make_unique<StockTimeline>();
  StockSummary& summary = timeline->summary_;
  summary.nominal_ap_mm = settings.point.ap;

  const ProgramPlan plan = read_plan(in);
  const Eigen::AlignedBox3d extent = stock_extent(in, plan.blk_form, summary);
  summary.box = extent;
  const EvaluatedSections evaluated = evaluated_sections(plan.sections);
  const double cell = stock_cell(stock, extent, evaluated, summary);
  HeightField field = initial_field(stock, extent, cell);
  summary.cell_mm = cell;
  summary.nx = field.grid().nx;
  summary.ny = field.grid().ny;

  timeline->before_.resize(plan.sections.size());
  Sweep sweep(std::move(field), plan.sections, evaluated.last, settings.point.cl_point, summary,
              timeline->before_);
  read_program(in, settings.sample_spacing_mm, [&](const Chunk& chunk) {
    for (const Slot& slot : chunk.slots) sweep.take(slot);
  });
  summary.memory_bytes = sweep.finish();
  summary.build_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return timeline;
}

}  // namespace vcpost::post
