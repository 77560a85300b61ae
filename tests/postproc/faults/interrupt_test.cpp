// The interrupt module and AtomicFile in process: the table of temporary
// files (registration, release, a full table), AtomicFile's commit and
// clean-up, a file-size limit as a write error, and signals arriving while
// threads create and commit files (in a forked child, so the test process
// keeps its own handlers).
#include "postproc/cli/interrupt.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "postproc/cli/atomic_file.h"
#include "postproc/cli/commands.h"
#include "tests/postproc/faults/child_process.h"

namespace vcpost::cli {
namespace {

namespace fs = std::filesystem;

fs::path fresh_folder() {
  std::string pattern = (fs::temp_directory_path() / "vcpost-interrupt-XXXXXX").string();
  return ::mkdtemp(pattern.data());
}

TEST(TemporaryRegistration, RegistersUntilReleasedAndRefusesAFullTable) {
  const fs::path folder = fresh_folder();
  const int baseline = registered_temporary_files();
  {
    TemporaryRegistration r;
    std::string pattern = (folder / ".x.XXXXXX").string();
    const int fd = r.create(pattern);
    ASSERT_GE(fd, 0);
    ::close(fd);
    EXPECT_EQ(pattern.find("XXXXXX"), std::string::npos) << pattern;
    EXPECT_TRUE(fs::exists(pattern));
    EXPECT_EQ(registered_temporary_files(), baseline + 1);
    r.release();
    EXPECT_EQ(registered_temporary_files(), baseline);
    fs::remove(pattern);
  }
  // The table has 64 slots: the 65th file is refused with EMFILE and
  // creates nothing.
  std::vector<std::unique_ptr<TemporaryRegistration>> all;
  int refused_errno = 0;
  for (int i = 0; i < 65; ++i) {
    auto r = std::make_unique<TemporaryRegistration>();
    std::string pattern = (folder / ".t.XXXXXX").string();
    const int fd = r->create(pattern);
    if (fd < 0) {
      refused_errno = errno;
      break;
    }
    ::close(fd);
    all.push_back(std::move(r));
  }
  EXPECT_EQ(static_cast<int>(all.size()), 64 - baseline);
  EXPECT_EQ(refused_errno, EMFILE);
  EXPECT_EQ(test::list_folder(folder).size(), all.size());
  all.clear();  // released, not removed: removing is AtomicFile's job
  EXPECT_EQ(registered_temporary_files(), baseline);
  fs::remove_all(folder);
}

TEST(AtomicFile, CommitRenamesAndDestructionRemoves) {
  const fs::path folder = fresh_folder();
  const int baseline = registered_temporary_files();
  {
    AtomicFile f(folder / "out.nc");
    f.write("G1 X1\n");
    EXPECT_EQ(test::list_folder(folder).size(), 1u);  // the temporary file only
    EXPECT_EQ(registered_temporary_files(), baseline + 1);
    f.commit();
  }
  EXPECT_EQ(test::read_file(folder / "out.nc"), "G1 X1\n");
  {
    AtomicFile f(folder / "other.nc");
    f.write("half");
  }  // not committed
  EXPECT_EQ(test::list_folder(folder), std::vector<std::string>{"out.nc"});
  EXPECT_EQ(registered_temporary_files(), baseline);
  fs::remove_all(folder);
}

TEST(AtomicFile, FileSizeLimitIsAnErrorNamingTheFile) {
  // In a child: 1000-byte RLIMIT_FSIZE, SIGXFSZ ignored as main() does;
  // 5000 bytes must fail with EFBIG's message, leaving the folder empty.
  const fs::path folder = fresh_folder();
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{1000, 1000};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    int code = 10;
    try {
      AtomicFile f(folder / "big.nc");
      f.write(std::string(5000, 'x'));
      f.commit();
    } catch (const CommandError& e) {
      const std::string expected = "cannot write '" + (folder / "big.nc").string() +
                                   "': File too large (nothing written: free some space or "
                                   "raise the limit, then run again)";
      code = e.what() == expected && e.exit_code() == exit_input_error ? 0 : 11;
    }
    ::_exit(code);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "10: no error, 11: another message or exit code";
  EXPECT_EQ(test::list_folder(folder), std::vector<std::string>{});
  fs::remove_all(folder);
}

TEST(InterruptHandler, NoTemporaryFileSurvivesASignalAmidBusyThreads) {
  // Two threads create, write and commit (or drop) files as fast as they
  // can; the main thread sends SIGINT to the process. Whatever moment the
  // signal hits, the folder may hold committed files but no temporary one,
  // and the child dies by SIGINT. 20 rounds.
  for (int round = 0; round < 20; ++round) {
    SCOPED_TRACE(round);
    const fs::path folder = fresh_folder();
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      ::close(STDERR_FILENO);  // the one-line message is checked by the binary's tests
      install_signal_handlers();
      std::atomic<int> names{0};
      auto busy = [&] {
        for (;;) {
          const int n = names.fetch_add(1);
          try {
            AtomicFile f(folder / ("f" + std::to_string(n)));
            f.write(std::string(4096, 'x'));
            if (n % 2 == 0) f.commit();
          } catch (const CommandError&) {
            // EINTR from create() once the handler runs: keep going
          }
        }
      };
      std::thread a(busy), b(busy);
      // Once the threads are under way (a loaded machine may start them
      // late), then 0 to 19 ms more: the signal falls at varied moments.
      while (names.load() < 8) std::this_thread::sleep_for(std::chrono::microseconds(200));
      std::this_thread::sleep_for(std::chrono::milliseconds(round));
      ::kill(::getpid(), SIGINT);
      std::this_thread::sleep_for(std::chrono::seconds(5));
      ::_exit(99);  // not reached: the handler ends the process
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << status;
    int temporaries = 0, committed = 0;
    for (const auto& name : test::list_folder(folder)) {
      (name[0] == '.' ? temporaries : committed) += 1;
    }
    EXPECT_EQ(temporaries, 0) << test::joined(test::list_folder(folder));
    EXPECT_GT(committed, 0);  // the threads did get going before the signal
    fs::remove_all(folder);
  }
}

}  // namespace
}  // namespace vcpost::cli
