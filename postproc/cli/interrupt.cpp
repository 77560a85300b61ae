#include "postproc/cli/interrupt.h"

#include <pthread.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <ctime>

namespace vcpost::cli {
namespace {

// The signals that end a run; SIGXFSZ is ignored instead (see the header).
constexpr std::array<int, 4> kSignals{SIGINT, SIGTERM, SIGHUP, SIGPIPE};
// A crash must not leave a temporary file either; these keep their core dump.
constexpr std::array<int, 5> kFaults{SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};

// Slot states: free -> claimed (path being written by its owner) -> live
// (the handler may read the path) -> free.
enum SlotState : int { slot_free = 0, slot_claimed = 1, slot_live = 2 };

struct Slot {
  std::atomic<int> state{slot_free};
  char path[PATH_MAX] = {};
};

constexpr int kSlots = 64;
Slot g_slots[kSlots];
// Threads inside TemporaryRegistration::create (between claiming a slot and
// publishing it); the handler waits for them so no file escapes the sweep.
std::atomic<int> g_creating{0};
// Set once by the first handler; a create() that sees it makes no file.
std::atomic<int> g_handling{0};
// Outputs renamed into place so far (for an honest message).
std::atomic<int> g_committed{0};
// Standard output has delivered bytes: a SIGPIPE now is a reader that has
// seen enough (`| head`), not a failure worth a message.
std::atomic<int> g_delivered{0};

static_assert(std::atomic<int>::is_always_lock_free, "the handler needs lock-free atomics");

sigset_t handled_signals() {
  sigset_t set;
  sigemptyset(&set);
  for (int sig : kSignals) sigaddset(&set, sig);
  return set;
}

const char* signal_name(int sig) {
  switch (sig) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    case SIGPIPE:
      return "SIGPIPE";
    case SIGSEGV:
      return "SIGSEGV";
    case SIGBUS:
      return "SIGBUS";
    case SIGFPE:
      return "SIGFPE";
    case SIGILL:
      return "SIGILL";
    case SIGABRT:
      return "SIGABRT";
    default:
      return "a signal";
  }
}

// Appends `text` to buf at *used, keeping room for the final newline.
void append(char* buf, std::size_t size, std::size_t* used, const char* text) {
  for (; *text && *used + 1 < size; ++text) buf[(*used)++] = *text;
}

void append_number(char* buf, std::size_t size, std::size_t* used, int n) {
  char digits[12];
  int count = 0;
  do {
    digits[count++] = static_cast<char>('0' + n % 10);
    n /= 10;
  } while (n > 0 && count < 11);
  while (count > 0 && *used + 1 < size) buf[(*used)++] = digits[--count];
}

bool is_fault(int sig) { return std::ranges::find(kFaults, sig) != kFaults.end(); }

// Waits (at most a second) for threads inside create(). Creators block the
// async signals and hold no lock, so this is a few system calls long; the
// bound only matters for a fault inside create() on this very thread.
void wait_for_creators() {
  timespec start{}, now{};
  ::clock_gettime(CLOCK_MONOTONIC, &start);
  while (g_creating.load() != 0) {
    ::clock_gettime(CLOCK_MONOTONIC, &now);
    if (now.tv_sec - start.tv_sec > 1) return;
  }
}

// Only async-signal-safe calls below: atomics, unlink, write, sigaction,
// pthread_sigmask, clock_gettime, raise, _exit, pause.
void on_signal(int sig) {
  if (g_handling.exchange(1) != 0) {
    // Another thread is already cleaning up and will end the process.
    for (;;) ::pause();
  }
  const int saved_errno = errno;
  wait_for_creators();
  for (Slot& slot : g_slots) {
    if (slot.state.load(std::memory_order_acquire) == slot_live) ::unlink(slot.path);
  }
  char line[160];
  std::size_t used = 0;
  append(line, sizeof line, &used,
         is_fault(sig) ? "vcpost: internal error: crashed with " : "vcpost: interrupted by ");
  append(line, sizeof line, &used, signal_name(sig));
  const int committed = g_committed.load();
  if (committed == 0) {
    append(line, sizeof line, &used, "; no output written");
  } else {
    append(line, sizeof line, &used, "; unfinished outputs removed, ");
    append_number(line, sizeof line, &used, committed);
    append(line, sizeof line, &used, " written before");
  }
  line[used++] = '\n';
  if (!(sig == SIGPIPE && g_delivered.load() != 0)) {
    [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, line, used);
  }

  // Die by the signal itself, so the parent sees how the run ended.
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigemptyset(&default_action.sa_mask);
  ::sigaction(sig, &default_action, nullptr);
  sigset_t only;
  sigemptyset(&only);
  sigaddset(&only, sig);
  ::pthread_sigmask(SIG_UNBLOCK, &only, nullptr);
  (void)::raise(sig);  // on failure, the _exit below ends the process
  errno = saved_errno;
  ::_exit(128 + sig);  // not reached: the default action of these signals ends the process
}

}  // namespace

void install_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  // One handler at a time per thread: the others wait (see on_signal).
  action.sa_mask = handled_signals();
  for (int sig : kSignals) {
    struct sigaction previous {};
    ::sigaction(sig, nullptr, &previous);
    if (previous.sa_handler == SIG_IGN) continue;
    ::sigaction(sig, &action, nullptr);
  }
  for (int sig : kFaults) {
    // A handler already there (a sanitizer's, a debugger's) reports better.
    struct sigaction previous {};
    ::sigaction(sig, nullptr, &previous);
    if (previous.sa_handler != SIG_DFL) continue;
    ::sigaction(sig, &action, nullptr);
  }
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  ::sigaction(SIGXFSZ, &ignore, nullptr);
}

void standard_output_delivered() { g_delivered.store(1); }
void standard_output_is_the_only_output() { g_delivered.store(1); }

int TemporaryRegistration::create(std::string& pattern) {
  if (slot_ >= 0) {
    errno = EBUSY;
    return -1;
  }
  if (pattern.size() >= PATH_MAX) {
    errno = ENAMETOOLONG;
    return -1;
  }
  // No handler may run on this thread while the file exists unregistered;
  // a handler on another thread waits for g_creating to fall to zero.
  const sigset_t blocked = handled_signals();
  sigset_t previous;
  ::pthread_sigmask(SIG_BLOCK, &blocked, &previous);
  g_creating.fetch_add(1);
  int fd = -1;
  int error = 0;
  if (g_handling.load() != 0) {
    error = EINTR;  // the process is ending: make nothing the sweep would miss
  } else {
    for (int i = 0; i < kSlots; ++i) {
      int expected = slot_free;
      if (g_slots[i].state.compare_exchange_strong(expected, slot_claimed)) {
        slot_ = i;
        break;
      }
    }
    if (slot_ < 0) {
      error = EMFILE;
    } else {
      fd = ::mkstemp(pattern.data());
      if (fd < 0) {
        error = errno;
        g_slots[slot_].state.store(slot_free);
        slot_ = -1;
      } else {
        std::memcpy(g_slots[slot_].path, pattern.c_str(), pattern.size() + 1);
        g_slots[slot_].state.store(slot_live, std::memory_order_release);
      }
    }
  }
  g_creating.fetch_sub(1);
  ::pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  if (fd < 0) errno = error;
  return fd;
}

void TemporaryRegistration::release() {
  if (slot_ < 0) return;
  g_slots[slot_].state.store(slot_free, std::memory_order_release);
  slot_ = -1;
}

void TemporaryRegistration::committed() {
  if (slot_ < 0) return;
  g_committed.fetch_add(1);
  release();
}

int registered_temporary_files() {
  int count = 0;
  for (const Slot& slot : g_slots) count += slot.state.load() == slot_live ? 1 : 0;
  return count;
}

}  // namespace vcpost::cli
