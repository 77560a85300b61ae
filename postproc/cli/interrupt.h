// Signals that end a run early (SIGINT, SIGTERM, SIGHUP, SIGPIPE) and the
// temporary output files they must not leave behind.
//
// The handler only touches a fixed table of paths (no allocation, no locks,
// lock-free atomics), so it is async-signal-safe and does not care which
// thread the kernel picks to run it. On a signal it removes every
// registered temporary file, writes one line to stderr
//   vcpost: interrupted by SIGINT; no output written
// (or, once some output was already renamed into place,
//   vcpost: interrupted by SIGINT; unfinished outputs removed, 1 written before)
// and re-raises the signal with its default action, so the parent (a shell,
// make, a CAM toolchain) sees a death by that signal: shells report exit
// status 128 + signal number (130 for SIGINT, 143 for SIGTERM).
//
// A crash (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT) gets the same clean-up
// and "vcpost: internal error: crashed with SIGSEGV; ..." before its usual
// end (core dump included), unless a handler was already installed for it
// (AddressSanitizer's, say), which is then left in place.
//
// This is the CLI's only process-wide state; the core libraries never see it.
#pragma once

#include <string>

namespace vcpost::cli {

// Installs the handlers above and ignores SIGXFSZ, so that a file-size limit
// (ulimit -f) turns into a write error (EFBIG) that the writer reports,
// instead of killing the process with a core dump. A signal the process was
// started with ignored (nohup, `cmd &` in a script) stays ignored, as the
// shell meant. Call once, early in main, before any thread starts.
void install_signal_handlers();

// Standard output has delivered some of its bytes: a SIGPIPE from now on is
// a reader that stopped reading (`vcpost post ... -o - | head`), which ends
// the process by the signal as before but without a message.
void standard_output_delivered();

// The command's only output is standard output (moves, verify, deff,
// machines, explain): no file can be left unfinished, and a SIGPIPE at any
// point is its reader leaving (`vcpost moves f.nc | head -1`), a normal end
// of such a run: it ends by the signal without a message, as post does.
void standard_output_is_the_only_output();

// A temporary file that the signal handler removes, from its creation until
// release(). Create the file through this object so that no signal can fall
// between the file's creation and its registration. Not copyable.
class TemporaryRegistration {
 public:
  TemporaryRegistration() = default;
  TemporaryRegistration(const TemporaryRegistration&) = delete;
  TemporaryRegistration& operator=(const TemporaryRegistration&) = delete;
  ~TemporaryRegistration() { release(); }

  // Creates a new file from `pattern` (a path ending in "XXXXXX", as for
  // mkstemp; the X's are replaced, absolute or relative to the working
  // folder) and registers it. Returns the open descriptor, or -1 with errno
  // set (EMFILE when the table of 64 registrations is full).
  // REQUIRES: nothing registered yet.
  int create(std::string& pattern);

  // Stops removing the file on a signal: it was removed, or (committed())
  // renamed into place as a complete output.
  void release();
  void committed();

 private:
  int slot_ = -1;
};

// Number of temporary files registered now (for tests).
int registered_temporary_files();

}  // namespace vcpost::cli
