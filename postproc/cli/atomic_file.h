// Output files that appear whole or not at all.
#pragma once

#include <sys/types.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

#include "postproc/cli/interrupt.h"

namespace vcpost::cli {

class HeldOutput;

// A regular (or missing) target is written to a temporary file beside it
// (".NAME.XXXXXX" in the same folder, so the final rename cannot cross file
// systems) and renamed over it on commit(); an existing file keeps its mode.
// A symbolic link is followed: its target is the file replaced (the link
// stays; through_link() tells the caller to say so). A target that is not a
// regular file (a device such as /dev/null, a FIFO, a terminal) is never
// replaced: the bytes are held (HeldOutput) and written into it in place on
// commit(). A name for one of this process's own open files (/dev/stdout,
// /dev/stderr, /dev/fd/N, /proc/self/fd/N) is written in place into that
// descriptor on commit(), as the shell opened it: appended after `2>>log`,
// into the pipe after `| cat`; never replaced by a rename.
// A regular file with more than one hard link is refused: a rename
// would silently split it from its other names.
// Destroying it uncommitted removes the temporary file, and so does a
// SIGINT/SIGTERM/SIGHUP/SIGPIPE (interrupt.h): an error or an interrupt
// never leaves a half-written output or a stray temporary file.
// Every failure throws CommandError with exit 2 and a message naming the
// target and the system's reason: the folder is missing or not writable,
// the target is a folder, the disk is full (ENOSPC), a file-size limit was
// hit (EFBIG; SIGXFSZ is ignored by install_signal_handlers so the limit
// shows up here).
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  void write(std::string_view bytes);  // throws CommandError on a write error
  void commit();                       // flush, fsync, close, rename; throws CommandError

  const std::filesystem::path& temporary() const { return temporary_; }
  // A device, FIFO, terminal or an open descriptor of this process.
  bool in_place() const { return held_ != nullptr; }
  bool through_link() const { return written_ != target_; }
  const std::filesystem::path& written() const { return written_; }  // the link's target

 private:
  [[noreturn]] void fail(int error);  // removes the temporary file and throws
  void commit_in_place();

  std::filesystem::path target_, written_, temporary_;
  std::FILE* file_ = nullptr;
  std::unique_ptr<HeldOutput> held_;
  int descriptor_ = -1;  // >= 0: written in place into this open descriptor
  TemporaryRegistration registration_;
};

// True when both paths name the same existing file (the input must never be
// overwritten, whatever the spelling of the names).
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

// N when `path` names this process's open descriptor N (/dev/stdout,
// /dev/stderr, /dev/fd/N, /proc/self/fd/N, /proc/<its pid>/fd/N) at any
// link of its chain; else -1. Following such a link to its end leads to a
// name that is not the open file (a pipe's "pipe:[...]") or to a file the
// shell opened its own way (appending).
int own_descriptor(const std::filesystem::path& path);

// `path` with every symbolic link of its last component followed, also a
// dangling one (the file a write to it would create). Throws CommandError
// for a loop of links.
std::filesystem::path follow_links(const std::filesystem::path& path);

}  // namespace vcpost::cli
