// The input program's text for the commands that read one (post, report,
// moves, verify). A regular file is mapped into memory, not copied, and the
// pages the job is done with are dropped as it goes, so a program of
// gigabytes costs no more memory than a window of it. Standard input, a
// pipe or a device is copied as it arrives into an unlinked temporary file
// ($TMPDIR or /tmp) and mapped the same way: memory stays bounded whatever
// comes in. Text only: the first NUL byte refuses the input (a binary
// file, /dev/urandom, /dev/zero) with its line and column, as soon as it
// arrives.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace vcpost::cli {

class ProgramText {
 public:
  // path "-" is standard input. Throws CommandError (exit 2) when it cannot
  // be read or is not text.
  explicit ProgramText(const std::string& path);
  ProgramText(const ProgramText&) = delete;
  ProgramText& operator=(const ProgramText&) = delete;
  ~ProgramText();

  std::string_view view() const { return view_; }

  // The reader will not look before `offset` again: drops those pages from
  // memory (they are read back from the file if it does after all).
  void release_before(std::uint64_t offset);

 private:
  void map(int fd, std::size_t size, const std::string& name);
  void refuse_binary(const std::string& name) const;
  void refuse_cr_only(const std::string& name) const;

  void* map_ = nullptr;
  std::size_t map_size_ = 0;
  std::uint64_t released_ = 0;
  std::string_view view_;
};

}  // namespace vcpost::cli
