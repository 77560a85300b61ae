// Helpers shared by the G-code and CL verifiers (not part of the API).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "postproc/program/events.h"
#include "postproc/verify/verify.h"

namespace vcpost::verify {

// Collects violations up to a budget; counts all of them.
class ViolationSink {
 public:
  explicit ViolationSink(std::size_t keep) : keep_(keep) {}
  void add(Code code, std::uint32_t line, std::uint32_t column, std::uint32_t input_line,
           std::string message);
  std::uint64_t count() const { return count_; }
  std::uint64_t count_of(Code code) const;
  bool has_line(std::uint32_t line) const { return lines_.contains(line); }
  const std::vector<Violation>& violations() const { return kept_; }
  // Sorted by output line and column into result.violations / violation_count.
  void move_into(Result& result);

 private:
  std::size_t keep_;
  std::uint64_t count_ = 0;
  std::vector<Violation> kept_;
  std::map<Code, std::uint64_t> by_code_;
  std::set<std::uint32_t> lines_;
};

// Hands each change to Options::on_change, or keeps it in the Result;
// counts them by letter either way.
class ChangeSink {
 public:
  ChangeSink(Result& result, const std::function<void(const Change&)>& callback)
      : result_(result), callback_(callback) {}
  void add(Change change) {
    ++(change.letter == 'S' ? result_.s_changes : result_.f_changes);
    if (callback_) {
      callback_(change);
    } else {
      result_.changes.push_back(std::move(change));
    }
  }

 private:
  Result& result_;
  const std::function<void(const Change&)>& callback_;
};

// Two events equal in every field but their source's offset and column
// (and its line unless `compare_lines`). Positions are compared exactly.
bool same_event(const program::Event& a, const program::Event& b, bool compare_lines);

// The event as `vcpost moves` prints it, on one line (for messages).
std::string event_text(const program::Event& e);

}  // namespace vcpost::verify
