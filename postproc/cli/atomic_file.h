// Output files that appear whole or not at all.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

namespace vcpost::cli {

// Writes to a temporary file beside `target` and renames it over `target`
// on commit(); destroying it uncommitted removes the temporary file, so an
// error or an interrupt never leaves a half-written output.
// Throws CommandError when the folder is missing or not writable.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  void write(std::string_view bytes);  // throws CommandError on a write error (disk full)
  void commit();                       // flush, close, rename; throws CommandError

 private:
  std::filesystem::path target_, temporary_;
  std::FILE* file_ = nullptr;
};

// True when both paths name the same existing file (the input must never be
// overwritten, whatever the spelling of the names).
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

}  // namespace vcpost::cli
