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

std::string mm(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

}  // namespace

std::unique_ptr<StockTimeline> build_stock_timeline(std::string_view text,
                                                    const std::string& file_name, ProgramKind kind,
                                                    const gcode::Dialect& dialect,
                                                    const machines::MachineProfile& profile,
                                                    const PostSettings& settings,
                                                    const tools::ToolChoices& choices) {
  const auto started = std::chrono::steady_clock::now();
  const StockSettings& stock = *settings.stock;
  auto timeline = std::make_unique<StockTimeline>();
  StockSummary& summary = timeline->summary_;
  summary.nominal_ap_mm = settings.point.ap;

  // First read: the sections, their tools, the frames they work in (and
  // Klartext's BLK FORM). Samples only at the moves' ends.
  std::vector<SectionPlan> plans;
  std::optional<heidenhain::StockBox> blk_form;
  {
    PathReader reader(text, file_name, kind, dialect, profile, 1e6, false, choices,
                      settings.point.ap);
    reader.set_program_loader(settings.program_loader);
    Chunk chunk;
    while (reader.read(chunk, chunk_samples)) {
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
    }
    blk_form = reader.klartext_stock();
  }

  // Where the stock starts.
  Eigen::AlignedBox3d extent;
  if (stock.from_program) {
    std::optional<DeclaredStock> declared;
    if (kind == ProgramKind::cldata) {
      declared = cl_declared_stock(text, file_name);
    } else if (kind == ProgramKind::heidenhain && blk_form) {
      declared = klartext_declared_stock(blk_form->min, blk_form->max,
                                         file_name + ":" + std::to_string(blk_form->source.line));
    }
    if (!declared)
      throw vcpost::Error(Code::E4720,
                          file_name +
                              ": the program declares no stock (Klartext BLK FORM, APT CL "
                              "INSERT/Stock Size): give --stock-box or --stock-model");
    extent = declared->box;
    summary.source = declared->words + " at " + declared->where;
  } else if (stock.box) {
    extent = *stock.box;
    summary.source = "--stock-box";
  } else {
    for (const Eigen::Vector3f& c : *stock.triangles) extent.extend(c.cast<double>());
    summary.source = "--stock-model " + stock.model_name;
  }
  summary.box = extent;

  // The cell: given, or from the smallest evaluated tool, coarsened to fit
  // the memory the field and its copies may take.
  std::uint32_t evaluated = 0;
  std::uint32_t last_evaluated = 0;  // no section after it needs the stock
  double smallest = 0;
  for (const SectionPlan& p : plans) {
    if (!p.section || !p.section->postable) continue;
    ++evaluated;
    last_evaluated = p.section->index;
    const double d = p.section->entry->diameter;
    smallest = smallest > 0 ? std::min(smallest, d) : d;
  }
  auto need = [&](double cell) {
    const double nx = std::ceil(extent.sizes().x() / cell),
                 ny = std::ceil(extent.sizes().y() / cell);
    return (1.0 + evaluated) * nx * ny * sizeof(float);
  };
  const auto limit = static_cast<double>(stock.memory_limit);
  double cell = 0;
  if (stock.cell_mm) {
    cell = *stock.cell_mm;
    summary.cell_note = "--stock-cell";
    if (need(cell) > limit)
      throw vcpost::Error(Code::E4724, "the stock at --stock-cell " + mm(cell) + " mm needs " +
                                           mm(std::ceil(need(cell) / (1 << 20))) +
                                           " MB (the field and " + std::to_string(evaluated) +
                                           " copies, one per evaluated section), above " +
                                           "--stock-memory " +
                                           std::to_string(stock.memory_limit >> 20) +
                                           " MB: give a coarser cell or more memory");
  } else {
    cell = std::clamp(smallest > 0 ? smallest * kCellPerDiameter : kMaxCell, kMinCell, kMaxCell);
    summary.cell_note = "the smallest evaluated tool's D/50 within [0.05, 1] mm";
    if (need(cell) > limit) {
      const double fine = cell;
      while (need(cell) > limit) cell *= 1.05;
      cell = std::ceil(cell * 1000) / 1000;
      summary.cell_note = "coarsened from " + mm(fine) + " mm to fit --stock-memory " +
                          std::to_string(stock.memory_limit >> 20) + " MB";
    }
  }
  // The engine's own check is per field; the copies are counted above.
  HeightField field =
      stock.triangles && !stock.from_program && !stock.box
          ? HeightField::from_triangles(*stock.triangles, cell, stock.memory_limit)
          : HeightField::block(extent.min(), extent.max(), cell, stock.memory_limit);
  summary.cell_mm = cell;
  summary.nx = field.grid().nx;
  summary.ny = field.grid().ny;

  // Second read: every section's moves swept, a copy kept at the start of
  // each evaluated section.
  timeline->before_.resize(plans.size());
  std::shared_ptr<const HeightField> last_copy;
  std::uint64_t memory = field.memory_bytes();
  bool cut_since_copy = true;
  {
    PathReader reader(text, file_name, kind, dialect, profile, settings.sample_spacing_mm, false,
                      choices, settings.point.ap);
    reader.set_program_loader(settings.program_loader);
    Chunk chunk;
    std::vector<Eigen::Vector3d> tips;
    std::optional<Cutter> cutter;
    std::optional<std::uint32_t> current;
    bool swept_any = false;
    bool unknown_tool = false;  // the current section's tool shape is unknown, not yet warned
    auto flush = [&] {
      if (cutter && !tips.empty()) {
        field.cut_path(*cutter, tips);
        cut_since_copy = true;
        swept_any = true;
      }
      tips.clear();
    };
    auto open_section = [&](std::uint32_t index) {
      flush();
      if (current && swept_any) summary.swept.push_back(*current);
      current = index;
      swept_any = false;
      cutter.reset();
      unknown_tool = false;
      const SectionPlan& plan = plans.at(index);
      const ToolSection& s = *plan.section;
      if (s.postable) {
        if (cut_since_copy || !last_copy) {
          if (index == last_evaluated) {  // nothing is swept after it: the field, not a copy
            last_copy = std::make_shared<const HeightField>(std::move(field));
          } else {
            last_copy = std::make_shared<const HeightField>(field);
            memory += last_copy->memory_bytes();
            ++summary.copies;
          }
          cut_since_copy = false;
        }
        timeline->before_[index] = std::make_shared<FieldDepth>(last_copy);
      }
      if (plan.tilted) {
        summary.warnings.push_back(
            std::string(to_string(Code::W4731)) + ": " + named(s) +
            " works in a tilted plane (3+2): its tilted moves are not swept (the stock is a "
            "height field along the machine's Z) and its tilted points take --ap");
      }
      if (index >= last_evaluated) return;  // nothing evaluated after it: not swept
      cutter = cutter_of(s);
      unknown_tool = !cutter;  // warned at its first cutting move, if it has one
    };
    while (reader.read(chunk, chunk_samples)) {
      for (const Slot& slot : chunk.slots) {
        if (slot.section != current) open_section(slot.section);
        if (slot.kind == SlotKind::rapid || slot.break_pass) flush();
        if (slot.kind != SlotKind::sample && slot.kind != SlotKind::kept) continue;
        if (!cutter) {
          if (unknown_tool) {
            const ToolSection& s = *plans.at(slot.section).section;
            summary.warnings.push_back(std::string(to_string(Code::W4730)) + ": " + named(s) +
                                       ": its tool's shape is unknown (" +
                                       (s.entry ? s.entry->describe() : std::string("no tool")) +
                                       "): not swept, the stock keeps its material there");
            unknown_tool = false;
          }
          continue;
        }
        if (slot.sample.frame != nullptr) {
          flush();
          continue;
        }
        const geometry::Tool& tool = cutter->tool;
        const Eigen::Vector3d origin =
            geometry::tool_origin(slot.sample.point, tool, settings.point.cl_point);
        tips.push_back(origin - Eigen::Vector3d(0, 0, tool.corner_radius));
        if (tips.size() >= kTipsPerCut) {
          const Eigen::Vector3d last = tips.back();
          flush();
          tips.push_back(last);
        }
      }
    }
    flush();
    if (current && swept_any) summary.swept.push_back(*current);
  }
  summary.memory_bytes = memory;
  summary.build_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return timeline;
}

}  // namespace vcpost::post
