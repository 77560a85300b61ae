// Output files that appear whole or not at all.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

#include "postproc/cli/interrupt.h"

namespace vcpost::cli {

// Writes to a temporary file beside `target` (".NAME.XXXXXX" in the same
// folder, so the final rename cannot cross file systems) and renames it over
// `target` on commit(). Destroying it uncommitted removes the temporary
// file, and so does a SIGINT/SIGTERM/SIGHUP/SIGPIPE (interrupt.h): an
// error or an interrupt never leaves a half-written output or a stray
// temporary file.
// Every failure throws CommandError with exit 2 and a message naming the
// target and the system's reason: the folder is missing or not writable,
// the disk is full (ENOSPC), a file-size limit was hit (EFBIG; SIGXFSZ is
// ignored by install_signal_handlers so the limit shows up here).
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  void write(std::string_view bytes);  // throws CommandError on a write error
  void commit();                       // flush, fsync, close, rename; throws CommandError

  const std::filesystem::path& temporary() const { return temporary_; }

 private:
  [[noreturn]] void fail(int error);  // removes the temporary file and throws

  std::filesystem::path target_, temporary_;
  std::FILE* file_ = nullptr;
  TemporaryRegistration registration_;
};

// True when both paths name the same existing file (the input must never be
// overwritten, whatever the spelling of the names).
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

}  // namespace vcpost::cli
