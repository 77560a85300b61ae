#include "postproc/tools/program_tools.h"

#include "core/units.h"

namespace vcpost::tools {
namespace {

constexpr std::size_t kMaxNotes = 100;  // a program of unreadable lines still keeps memory flat

}  // namespace

void ProgramTools::on_comment(std::string_view text, const std::string& where, bool inches) {
  if (pycam_.takes(text)) {
    if (auto found = pycam_.read(text, where)) take(std::move(*found), where, inches);
    return;
  }
  if (auto cut = pycam_.cut_short()) take(std::move(*cut), where, inches);
  if (auto found = read_tool_comment(text)) take(std::move(*found), where, inches);
}

void ProgramTools::take(CommentTool found, const std::string& where, bool inches) {
  if (!found.entry) {
    if (notes_.size() < kMaxNotes) {
      notes_.push_back(where + ": " + std::string(to_string(found.format)) +
                       " tool comment not read (" + found.note + "); its tool stays unknown");
    }
    return;
  }
  ToolEntry entry = std::move(*found.entry);
  if (inches) {
    entry.diameter *= kMmPerInch;
    if (entry.corner_radius) *entry.corner_radius *= kMmPerInch;
  }
  if (entry.where.empty()) entry.where = where;
  on_entry(std::move(entry));
}

void ProgramTools::on_entry(ToolEntry entry) {
  if (entry.number) {
    const int n = *entry.number;
    numbered_.insert_or_assign(n, std::move(entry));
    return;
  }
  // Unnumbered: waits for the next tool change or motion (on_motion).
  pending_ = std::move(entry);
}

void ProgramTools::on_tool_change(int number) {
  number_ = number;
  moved_ = false;
  section_.reset();
  if (pending_) {
    pending_->number = number;
    numbered_.insert_or_assign(number, std::move(*pending_));
    pending_.reset();
  }
}

void ProgramTools::on_motion() {
  if (pending_) {
    if (number_) {
      pending_->number = number_;
      numbered_.insert_or_assign(*number_, std::move(*pending_));
    } else {
      section_ = std::move(*pending_);
    }
    pending_.reset();
  }
  moved_ = true;
}

const ToolEntry* ProgramTools::current() const {
  if (number_) {
    const auto it = numbered_.find(*number_);
    return it == numbered_.end() ? nullptr : &it->second;
  }
  return section_ ? &*section_ : nullptr;
}

}  // namespace vcpost::tools
