// The in-process stock before each posted section (issue 44): the program
// read once ahead of the post job, every section's moves swept out of a
// height field with its tool's shape, and a copy of the field kept at the
// start of each section the job evaluates. ap at a point of that section is
// then the material's depth along the normal at its contact point in the
// stock as it stood before the section (docs/stock.md says why not after
// the section's own earlier passes).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "machines/profile.h"
#include "postproc/gcode/dialect.h"
#include "postproc/pipeline/point_evaluator.h"
#include "postproc/post/post_job.h"
#include "postproc/post/stock_summary.h"
#include "postproc/tools/tool_table.h"

namespace vcpost::post {

class StockTimeline {
 public:
  // The stock before `section` (ToolSection::index); null for a section
  // the job does not evaluate.
  const pipeline::MaterialDepth* before(std::uint32_t section) const {
    return section < before_.size() ? before_[section].get() : nullptr;
  }
  const StockSummary& summary() const { return summary_; }

 private:
  friend std::unique_ptr<StockTimeline> build_stock_timeline(std::string_view, const std::string&,
                                                             ProgramKind, const gcode::Dialect&,
                                                             const machines::MachineProfile&,
                                                             const PostSettings&,
                                                             const tools::ToolChoices&);
  std::vector<std::shared_ptr<const pipeline::MaterialDepth>> before_;
  StockSummary summary_;
};

// Reads the program twice ahead of the job (its sections and tools, then
// its moves) and builds the stock of settings.stock (which must be set);
// the sections from the last evaluated one on are not swept (nothing after
// them reads the stock).
// Throws vcpost::Error: E4720 (no stock declared where the program's was
// asked for), E4721/E4722 (a declaration it cannot take), E4724 (the
// field and its copies need more than --stock-memory at --stock-cell), the
// engine's own errors, and the readers' errors as the job's reading does.
std::unique_ptr<StockTimeline> build_stock_timeline(std::string_view text,
                                                    const std::string& file_name, ProgramKind kind,
                                                    const gcode::Dialect& dialect,
                                                    const machines::MachineProfile& profile,
                                                    const PostSettings& settings,
                                                    const tools::ToolChoices& choices);

}  // namespace vcpost::post
