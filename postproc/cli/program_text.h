// The input program's text for the post job. A regular file is mapped into
// memory, not copied, and the pages the job is done with are dropped as it
// goes, so a program of gigabytes costs no more memory than a window of it.
// Standard input (or a pipe) is read whole.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace vcpost::cli {

class ProgramText {
 public:
  // path "-" is standard input. Throws CommandError when it cannot be read.
  explicit ProgramText(const std::string& path);
  ProgramText(const ProgramText&) = delete;
  ProgramText& operator=(const ProgramText&) = delete;
  ~ProgramText();

  std::string_view view() const { return view_; }

  // The reader will not look before `offset` again: drops those pages from
  // memory (they are read back from the file if it does after all).
  void release_before(std::uint64_t offset);

 private:
  std::string copy_;  // standard input
  void* map_ = nullptr;
  std::size_t map_size_ = 0;
  std::uint64_t released_ = 0;
  std::string_view view_;
};

}  // namespace vcpost::cli
