// Running the real vcpost binary from tests: fork/exec with stdout and
// stderr captured in files, optional resource limit, user, working folder
// and a signal sent mid-run. Header-only so the occt tests can use it too
// (each test folder is its own executable).
#pragma once

#include <fcntl.h>
#include <grp.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../temp_folder.h"

namespace vcpost::test {

using ::vcpost::testing::Folder;

struct ChildOptions {
  std::vector<std::string> argv;      // argv[0] is the program's path
  std::filesystem::path stdout_file;  // required: where stdout goes
  std::filesystem::path stderr_file;  // required: where stderr goes
  std::filesystem::path stdin_file;   // empty: /dev/null
  int stdout_fd = -1;                 // >= 0: stdout is this descriptor (e.g. a pipe), not the file
  std::optional<rlim_t> file_size_limit;  // RLIMIT_FSIZE in bytes, set in the child
  std::optional<rlim_t> memory_limit;     // RLIMIT_AS in bytes, set in the child
  // Killed (SIGKILL) when still running after this many seconds: a hang
  // fails the test instead of stopping the suite.
  std::optional<double> timeout_s;
  std::optional<uid_t> run_as;  // setresuid/setresgid (same id) in the child
  // Called in the parent while the child runs, with its pid; returns when
  // the child may be left to finish (e.g. after sending it a signal).
  std::function<void(pid_t)> while_running;
};

struct ChildResult {
  bool exited = false;  // normal exit (then exit_code), or killed (then signal)
  int exit_code = -1;
  int signal = 0;
  std::string out, err;
  double seconds = 0;
  long peak_rss_kb = 0;  // the child's peak resident set size (getrusage's ru_maxrss), KB
  // What a shell would show as $?.
  int shell_status() const { return exited ? exit_code : 128 + signal; }
};

inline std::string read_file(const std::filesystem::path& path) {
  if (!std::filesystem::is_regular_file(path)) return {};  // e.g. /dev/full: endless zeros
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// FNV-1a, 64 bits: enough to tell a changed input file from the same bytes.
inline std::uint64_t file_hash(const std::filesystem::path& path) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : read_file(path)) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

// Every entry of a folder (dot files included), sorted, names only.
inline std::vector<std::string> list_folder(const std::filesystem::path& folder) {
  std::vector<std::string> names;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

inline std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& n : names) text += (text.empty() ? "" : ", ") + n;
  return "[" + text + "]";
}

inline ChildResult run_child(const ChildOptions& options) {
  // Everything the child needs is prepared before fork: after it, only
  // async-signal-safe calls.
  std::vector<char*> argv;
  for (const auto& a : options.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::string in = options.stdin_file.empty() ? "/dev/null" : options.stdin_file.string();
  const std::string out = options.stdout_file.string(), err = options.stderr_file.string();
  const auto started = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) return {};
  if (pid == 0) {
    // The handled signals start at their defaults whatever the test runner
    // ignores (a background job ignores SIGINT), and none is blocked.
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGXFSZ}) ::signal(sig, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    const int fd_in = ::open(in.c_str(), O_RDONLY);
    const int fd_out = options.stdout_fd >= 0
                           ? options.stdout_fd
                           : ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
    const int fd_err = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
    if (fd_in < 0 || fd_out < 0 || fd_err < 0) ::_exit(120);
    ::dup2(fd_in, 0);
    ::dup2(fd_out, 1);
    ::dup2(fd_err, 2);
    if (options.file_size_limit) {
      const rlimit limit{*options.file_size_limit, *options.file_size_limit};
      if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(121);
    }
    if (options.memory_limit) {
      const rlimit limit{*options.memory_limit, *options.memory_limit};
      if (::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(123);
    }
    if (options.run_as) {
      const uid_t id = *options.run_as;
      if (::setgroups(0, nullptr) != 0 || ::setresgid(id, id, id) != 0 ||
          ::setresuid(id, id, id) != 0) {
        ::_exit(122);
      }
    }
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  if (options.while_running) options.while_running(pid);
  if (options.timeout_s) {
    const auto end = started + std::chrono::duration<double>(*options.timeout_s);
    for (;;) {
      siginfo_t info{};
      if (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) != 0 ||
          info.si_pid != 0) {
        break;  // ended (not reaped yet)
      }
      if (std::chrono::steady_clock::now() > end) {
        ::kill(pid, SIGKILL);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  int status = 0;
  rusage usage{};
  while (::wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  ChildResult r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  r.exited = WIFEXITED(status);
  r.exit_code = r.exited ? WEXITSTATUS(status) : -1;
  r.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  r.peak_rss_kb = usage.ru_maxrss;
  r.out = read_file(options.stdout_file);
  r.err = read_file(options.stderr_file);
  return r;
}

// Whether `pid` is still running (not yet a zombie that waitpid would reap).
inline bool still_running(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string pid_field, comm, state;
  stat >> pid_field >> comm >> state;
  return stat && state != "Z" && state != "X";
}

// Waits until `folder` holds an entry starting with `prefix` while `pid`
// runs; false after `timeout_s` or when the child ended first.
inline bool wait_for_entry(const std::filesystem::path& folder, const std::string& prefix,
                           pid_t pid, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < end) {
    for (const auto& name : list_folder(folder)) {
      if (name.rfind(prefix, 0) == 0) return true;
    }
    if (!still_running(pid)) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

}  // namespace vcpost::test
