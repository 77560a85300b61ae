// Faults around a run of the real `vcpost` binary (issue 8): the output
// folder missing or read-only, the disk full (file-size limit, 1 MB tmpfs),
// standard output failing, SIGINT/SIGTERM mid-run, and a program that does
// not match its model. In every case: one clear line on stderr, a non-zero
// exit, no output file and no temporary file left in the output folder
// (listed), and the input files byte-identical (hashed before and after).
#include <gtest/gtest.h>

#include <cstdlib>
#include <regex>

#include "tests/postproc/faults/child_process.h"

namespace vcpost::test {
namespace {

namespace fs = std::filesystem;

const fs::path kSamples = fs::path(VCPOST_SOURCE_DIR) / "samples";
const std::string kVcpost = VCPOST_BINARY;

// The post job's options for the dome sample (D10 ball, 120 m/min).
std::vector<std::string> dome_job(const fs::path& program) {
  return {kVcpost,
          "post",
          program.string(),
          "--model",
          (kSamples / "dome.step").string(),
          "--tool",
          "ball:10",
          "--vc",
          "120",
          "--ap",
          "0.3",
          "--ae",
          "3",
          "-q"};
}

// A long G-code program (about 300,000 points on the wavy sample; posted
// with --spacing 0.05, about 1.5 s of CPU) from the sample generator beside
// vcpost, made once.
const fs::path& long_program() {
  static const fs::path path = [] {
    const fs::path generator =
        fs::path(kVcpost).parent_path().parent_path() / "samplegen" / "vcpost-samplegen";
    const fs::path out =
        fs::temp_directory_path() / ("vcpost-faults-wavy-" + std::to_string(::getpid()) + ".nc");
    if (!fs::exists(generator)) return fs::path();
    ChildOptions o;
    o.argv = {generator.string(), "path", "wavy", "--points", "300000", "--gcode", out.string()};
    o.stdout_file = out.string() + ".out";
    o.stderr_file = out.string() + ".err";
    const ChildResult r = run_child(o);
    fs::remove(o.stdout_file);
    fs::remove(o.stderr_file);
    if (!r.exited || r.exit_code != 0) return fs::path();
    std::atexit([] {
      fs::remove(fs::temp_directory_path() /
                 ("vcpost-faults-wavy-" + std::to_string(::getpid()) + ".nc"));
    });
    return out;
  }();
  return path;
}

std::vector<std::string> wavy_job(const fs::path& program) {
  return {kVcpost,
          "post",
          program.string(),
          "--model",
          (kSamples / "wavy.step").string(),
          "--tool",
          "ball:10",
          "--vc",
          "120",
          "--ap",
          "0.3",
          "--ae",
          "0.5",
          "--spacing",
          "0.05",
          "-q"};
}

// Runs vcpost with `args` + extra, stdout/stderr into files of `logs`.
ChildResult run_vcpost(std::vector<std::string> args, const Folder& logs,
                       const std::function<void(ChildOptions&)>& adjust = {}) {
  ChildOptions o;
  o.argv = std::move(args);
  o.stdout_file = logs / "stdout.txt";
  o.stderr_file = logs / "stderr.txt";
  if (adjust) adjust(o);
  return run_child(o);
}

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// The one line vcpost prints on an error (the whole of stderr with -q).
std::string one_line(const ChildResult& r) {
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  return r.err;
}

TEST(Faults, OutputFolderMissing) {
  // The folder of -o does not exist: vcpost does not create folders (a typo
  // in a path must not scatter files), so exit 2 naming the file.
  Folder work, logs;
  const fs::path program = kSamples / "dome_raster_a0_ae3.nc";
  const auto before = file_hash(program);
  const ChildResult r =
      run_vcpost(with(dome_job(program), {"-o", (work / "missing/out.nc").string()}), logs);
  EXPECT_EQ(r.shell_status(), 2);
  EXPECT_EQ(one_line(r), "vcpost: error: cannot write '" + (work / "missing/out.nc").string() +
                             "': cannot create a file in '" + (work / "missing").string() +
                             "': No such file or directory\n");
  EXPECT_TRUE(r.out.empty());
  EXPECT_EQ(list_folder(work.path()), std::vector<std::string>{});
  EXPECT_EQ(file_hash(program), before);
}

TEST(Faults, ReportFolderMissingLeavesNoProgramEither) {
  // -o is fine but the HTML report's folder is missing: the run fails (exit
  // 2) and the posted program must not be left behind on its own either.
  Folder work, logs;
  const fs::path program = kSamples / "dome_raster_a0_ae3.nc";
  const ChildResult r = run_vcpost(
      with(dome_job(program),
           {"-o", (work / "out.nc").string(), "--report", (work / "missing/r.html").string()}),
      logs);
  EXPECT_EQ(r.shell_status(), 2);
  EXPECT_NE(one_line(r).find("cannot write '" + (work / "missing/r.html").string() + "'"),
            std::string::npos);
  EXPECT_EQ(list_folder(work.path()), std::vector<std::string>{});
}

TEST(Faults, SummaryFolderMissingLeavesNoProgramEither) {
  // The same for --summary-json: its folder is checked before any work.
  Folder work, logs;
  const fs::path program = kSamples / "dome_raster_a0_ae3.nc";
  const ChildResult r =
      run_vcpost(with(dome_job(program), {"-o", (work / "out.nc").string(), "--summary-json",
                                          (work / "missing/s.json").string()}),
                 logs);
  EXPECT_EQ(r.shell_status(), 2);
  EXPECT_NE(one_line(r).find("cannot write '" + (work / "missing/s.json").string() + "'"),
            std::string::npos);
  EXPECT_EQ(list_folder(work.path()), std::vector<std::string>{});
}

// The id the child runs as: root ignores permission bits, so as root the
// read-only cases run as nobody (65534).
std::optional<uid_t> unprivileged() {
  return ::geteuid() == 0 ? std::optional<uid_t>(65534) : std::nullopt;
}

TEST(Faults, OutputFolderReadOnly) {
  Folder work, logs;
  const fs::path program = kSamples / "dome_raster_a0_ae3.nc";
  const auto before = file_hash(program);
  fs::create_directory(work / "ro");
  fs::create_directory(work / "rw");
  fs::permissions(work / "ro", fs::perms::owner_all | fs::perms::group_read |
                                   fs::perms::group_exec | fs::perms::others_read |
                                   fs::perms::others_exec);
  fs::permissions(work / "rw", fs::perms::all);
  fs::permissions(logs.path(), fs::perms::all);
  const auto as = [](ChildOptions& o) { o.run_as = unprivileged(); };
  // Control: the same user can post into a writable folder, so the failure
  // below is the folder's mode and nothing else.
  const ChildResult ok =
      run_vcpost(with(dome_job(program), {"-o", (work / "rw/out.nc").string()}), logs, as);
  ASSERT_EQ(ok.shell_status(), 0) << ok.err;
  EXPECT_EQ(list_folder(work / "rw"), std::vector<std::string>{"out.nc"});

  fs::permissions(work / "ro", fs::perms::owner_write, fs::perm_options::remove);
  const ChildResult r =
      run_vcpost(with(dome_job(program), {"-o", (work / "ro/out.nc").string()}), logs, as);
  EXPECT_EQ(r.shell_status(), 2);
  EXPECT_EQ(one_line(r), "vcpost: error: cannot write '" + (work / "ro/out.nc").string() +
                             "': cannot create a file in '" + (work / "ro").string() +
                             "': Permission denied\n");
  EXPECT_EQ(list_folder(work / "ro"), std::vector<std::string>{});
  EXPECT_EQ(file_hash(program), before);
}

TEST(Faults, FileSizeLimitIsADiskFullError) {
  // RLIMIT_FSIZE of 4 KiB (the dome program posts to about 14 KiB): the
  // write fails with EFBIG (SIGXFSZ is ignored), vcpost says so naming the
  // file, exits 2 and removes its temporary file.
  Folder work, logs;
  const fs::path program = kSamples / "dome_raster_a0_ae3.nc";
  ASSERT_GT(fs::file_size(program), 8192u);
  const auto before = file_hash(program);
  const ChildResult r = run_vcpost(with(dome_job(program), {"-o", (work / "out.nc").string()}),
                                   logs, [](ChildOptions& o) { o.file_size_limit = 4096; });
  EXPECT_EQ(r.shell_status(), 2) << r.err;
  EXPECT_EQ(one_line(r), "vcpost: error: cannot write '" + (work / "out.nc").string() +
                             "': File too large (nothing written: free some space or raise the "
                             "limit, then run again)\n");
  EXPECT_EQ(list_folder(work.path()), std::vector<std::string>{});
  EXPECT_EQ(file_hash(program), before);
}

TEST(Faults, StandardOutputFull) {
  // `-o -` to /dev/full: the program goes to stdout only once the job has
  // succeeded, and that final write fails with ENOSPC: exit 2, not 0.
  Folder logs;
  const fs::path program = kSamples / "dome_raster_a0_ae3.nc";
  const ChildResult r = run_vcpost(with(dome_job(program), {"-o", "-"}), logs,
                                   [](ChildOptions& o) { o.stdout_file = "/dev/full"; });
  EXPECT_EQ(r.shell_status(), 2) << r.err;
  EXPECT_NE(r.err.find("standard output"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
}

TEST(Faults, StandardOutputPipeClosed) {
  // `-o -` into a pipe nobody reads any more: the final write raises
  // SIGPIPE; vcpost says so in one line and dies by it (the shell: 141).
  Folder logs;
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  ::close(fds[0]);
  const fs::path program = kSamples / "dome_raster_a0_ae3.nc";
  const ChildResult r = run_vcpost(with(dome_job(program), {"-o", "-"}), logs,
                                   [&](ChildOptions& o) { o.stdout_fd = fds[1]; });
  ::close(fds[1]);
  EXPECT_FALSE(r.exited);
  EXPECT_EQ(r.signal, SIGPIPE);
  EXPECT_EQ(r.shell_status(), 141);
  EXPECT_EQ(r.err, "vcpost: interrupted by SIGPIPE; no output written\n");
}

TEST(Faults, SmallTmpfsIsFull) {
  // A real full file system: a 1 MB tmpfs in a private mount namespace
  // (needs root and `unshare -m`), the long program (over 6 MB posted).
  if (::geteuid() != 0) GTEST_SKIP() << "a tmpfs mount needs root";
  Folder probe_logs;
  ChildOptions probe;
  probe.argv = {"/usr/bin/unshare", "-m", "/bin/true"};
  probe.stdout_file = probe_logs / "out";
  probe.stderr_file = probe_logs / "err";
  if (!fs::exists(probe.argv[0]) || run_child(probe).shell_status() != 0)
    GTEST_SKIP() << "unshare -m is not permitted here";
  const fs::path& program = long_program();
  ASSERT_FALSE(program.empty()) << "vcpost-samplegen (build it) could not write the long program";
  Folder work, logs;
  const auto before = file_hash(program);
  const fs::path mount = work / "small";
  fs::create_directory(mount);
  std::string command = "mount -t tmpfs -o size=1m tmpfs '" + mount.string() + "' || exit 99; ";
  for (const auto& a : with(wavy_job(program), {"-o", (mount / "out.nc").string()})) {
    command += "'" + a + "' ";
  }
  command += "; rc=$?; ls -A '" + mount.string() + "'; exit $rc";
  const ChildResult r = run_vcpost({"/usr/bin/unshare", "-m", "/bin/sh", "-c", command}, logs);
  EXPECT_EQ(r.shell_status(), 2) << r.err;
  EXPECT_EQ(one_line(r), "vcpost: error: cannot write '" + (mount / "out.nc").string() +
                             "': No space left on device (nothing written: free some space or "
                             "raise the limit, then run again)\n");
  EXPECT_EQ(r.out, "") << "files left in the full tmpfs";
  EXPECT_EQ(file_hash(program), before);
}

struct Interrupt {
  int signal;
  const char* name;
  bool html;
};

void PrintTo(const Interrupt& c, std::ostream* out) {
  *out << c.name << (c.html ? " with --report" : "");
}

class Interrupted : public ::testing::TestWithParam<Interrupt> {};

TEST_P(Interrupted, LeavesNothingAndDiesByTheSignal) {
  // The signal comes 0.3 s after the output's temporary file appeared, in
  // the middle of posting: the handler removes the temporary file(s), says
  // so in one line and dies by the same signal (the shell sees 128 + n).
  const Interrupt& c = GetParam();
  const fs::path& program = long_program();
  ASSERT_FALSE(program.empty()) << "vcpost-samplegen (build it) could not write the long program";
  Folder work, logs;
  const auto before = file_hash(program);
  const auto model_before = file_hash(kSamples / "wavy.step");
  auto args = with(wavy_job(program), {"-o", (work / "out.nc").string()});
  if (c.html) args = with(args, {"--report", (work / "r.html").string()});
  bool seen = false, running = false;
  const ChildResult r = run_vcpost(args, logs, [&](ChildOptions& o) {
    o.while_running = [&](pid_t pid) {
      seen = wait_for_entry(work.path(), ".out.nc.", pid, 30);
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
      running = still_running(pid);
      ::kill(pid, c.signal);
    };
  });
  ASSERT_TRUE(seen) << "no temporary output appeared: " << r.err;
  ASSERT_TRUE(running) << "the run ended before the signal (" << r.seconds << " s)";
  EXPECT_FALSE(r.exited);
  EXPECT_EQ(r.signal, c.signal);
  EXPECT_EQ(r.shell_status(), 128 + c.signal);
  EXPECT_EQ(r.err, std::string("vcpost: interrupted by ") + c.name + "; no output written\n");
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(list_folder(work.path()), std::vector<std::string>{});
  EXPECT_EQ(file_hash(program), before);
  EXPECT_EQ(file_hash(kSamples / "wavy.step"), model_before);
}

INSTANTIATE_TEST_SUITE_P(Signals, Interrupted,
                         ::testing::Values(Interrupt{SIGINT, "SIGINT", false},
                                           Interrupt{SIGTERM, "SIGTERM", false},
                                           Interrupt{SIGINT, "SIGINT", true},
                                           Interrupt{SIGTERM, "SIGTERM", true},
                                           Interrupt{SIGHUP, "SIGHUP", false}));

// The dome program with `offset` mm added to every X word of the lines
// from `from_line` on (1-based).
fs::path shifted_program(const Folder& work, double offset, std::size_t from_line) {
  std::istringstream in(read_file(kSamples / "dome_raster_a0_ae3.nc"));
  std::ostringstream out;
  static const std::regex x_word(R"(X(-?[0-9]+\.?[0-9]*))");
  std::string line;
  for (std::size_t n = 1; std::getline(in, line); ++n) {
    if (n < from_line) {
      out << line << '\n';
      continue;
    }
    std::string shifted;
    auto last = line.cbegin();
    for (std::sregex_iterator m(line.begin(), line.end(), x_word), end; m != end; ++m) {
      shifted.append(last, (*m)[0].first);
      char number[32];
      std::snprintf(number, sizeof number, "X%.6f", std::stod((*m)[1].str()) + offset);
      shifted += number;
      last = (*m)[0].second;
    }
    shifted.append(last, line.cend());
    out << shifted << '\n';
  }
  const fs::path path = work / "shifted.nc";
  std::ofstream(path, std::ios::binary) << out.str();
  return path;
}

std::size_t line_count(const fs::path& path) {
  const std::string text = read_file(path);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(Faults, ProgramBesideTheModel) {
  // Every X 500 mm off: the dome (R40) is nowhere near any point, so the
  // job refuses (exit 2) with the hint about work offset and units, and
  // writes no program.
  Folder work, logs;
  const fs::path program = shifted_program(work, 500, 1);
  const auto before = file_hash(program);
  const ChildResult r =
      run_vcpost(with(dome_job(program), {"-o", (work / "out.nc").string()}), logs);
  EXPECT_EQ(r.shell_status(), 2);
  EXPECT_NE(one_line(r).find("vcpost: error: the toolpath never touches the model ("),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("check the work offset and units"), std::string::npos);
  EXPECT_EQ(list_folder(work.path()), std::vector<std::string>{"shifted.nc"});
  EXPECT_EQ(file_hash(program), before);
}

TEST(Faults, ProgramAboveTheModelIsDiagnosed) {
  // A program of ball-centre points for a D10 ball on the dome (sphere R40
  // about the origin: every point 45 mm from it), posted with a D9.9 ball:
  // every point sits 45 - 40 - 4.95 = 0.05 mm above the model (stock left
  // on). The refusal (E2005) gives the lift heights and the likely causes.
  // The program's chords are within 0.0002 mm of the centre path, so every
  // point's lift is 0.05 mm within 0.002.
  const fs::path generator =
      fs::path(kVcpost).parent_path().parent_path() / "samplegen" / "vcpost-samplegen";
  ASSERT_TRUE(fs::exists(generator)) << generator;
  Folder work, logs;
  const fs::path tip = work / "tip.nc";
  ChildOptions o;
  o.argv = {generator.string(),
            "path",
            "dome",
            "--tool-diameter",
            "10",
            "--ae",
            "6",
            "--step",
            "1",
            "--chord-tolerance",
            "0.0002",
            "--radius",
            "43.26",
            "--gcode",
            tip.string()};
  o.stdout_file = (logs.path() / "gen.out").string();
  o.stderr_file = (logs.path() / "gen.err").string();
  const ChildResult g = run_child(o);
  ASSERT_TRUE(g.exited && g.exit_code == 0) << read_file(o.stderr_file);
  // The tip points to ball centres: + R on z.
  constexpr double kSphere = 40, kProgramRadius = 5, kToolRadius = 4.95;
  static const std::regex z_word(R"(Z(-?[0-9]+\.?[0-9]*))");
  std::string centres;
  const std::string text = read_file(tip);
  auto last = text.cbegin();
  for (std::sregex_iterator m(text.begin(), text.end(), z_word), end; m != end; ++m) {
    centres.append(last, (*m)[0].first);
    char number[32];
    std::snprintf(number, sizeof number, "Z%.6f", std::stod((*m)[1].str()) + kProgramRadius);
    centres += number;
    last = (*m)[0].second;
  }
  centres.append(last, text.cend());
  const fs::path program = work / "centre.nc";
  std::ofstream(program, std::ios::binary) << centres;
  fs::remove(tip);
  const auto before = file_hash(program);
  auto args = dome_job(program);
  *std::find(args.begin(), args.end(), "ball:10") = "ball:9.9";
  const ChildResult r =
      run_vcpost(with(args, {"--cl-point", "center", "-o", (work / "out.nc").string()}), logs);
  EXPECT_EQ(r.shell_status(), 2);
  const std::string line = one_line(r);
  EXPECT_NE(line.find("vcpost: error: the toolpath never touches the model ("), std::string::npos)
      << r.err;
  const double lift = kSphere + kProgramRadius - kSphere - kToolRadius;  // 0.05
  std::smatch m;
  static const std::regex heights(
      R"(: ([0-9]+) sit above it; lift height min ([0-9.]+), median ([0-9.]+), max ([0-9.]+) mm \(([0-9]+) points\))");
  ASSERT_TRUE(std::regex_search(line, m, heights)) << r.err;
  EXPECT_EQ(m[1].str(), m[5].str());
  EXPECT_GT(std::stoi(m[1].str()), 1000);
  for (int i = 2; i <= 4; ++i) EXPECT_NEAR(std::stod(m[i].str()), lift, 0.002) << m[i].str();
  static const std::regex causes(
      R"(([0-9]+) % of the points near the model sit ([0-9.]+) mm above it: likely stock to leave of about ([0-9.]+) mm \(post with --stock ([0-9.]+)[^,]*, or post the finishing program\), or a tool diameter ([0-9.]+) mm smaller than the program's.*--contact-tolerance above ([0-9.]+) mm)");
  ASSERT_TRUE(std::regex_search(line, m, causes)) << r.err;
  EXPECT_EQ(m[1].str(), "100");
  EXPECT_NEAR(std::stod(m[2].str()), lift, 0.002);
  EXPECT_NEAR(std::stod(m[3].str()), lift, 0.002);
  EXPECT_NEAR(std::stod(m[4].str()), lift, 0.002);  // the allowance that posts it
  EXPECT_NEAR(std::stod(m[5].str()), 2 * lift, 0.004);
  EXPECT_NEAR(std::stod(m[6].str()), lift, 0.002);
  EXPECT_EQ(line.find("no one offset dominates"), std::string::npos);
  EXPECT_EQ(list_folder(work.path()), std::vector<std::string>{"centre.nc"});
  EXPECT_EQ(file_hash(program), before);
}

TEST(Faults, ProgramHalfBesideTheModel) {
  // The second half of the lines 500 mm off: the first half touches, the
  // rest does not. A warning names the points without contact (the program
  // is complete and written: its blocks without contact keep the program's
  // S); --strict makes it exit 1 and leaves no file it refused.
  Folder work, logs;
  const fs::path program =
      shifted_program(work, 500, line_count(kSamples / "dome_raster_a0_ae3.nc") / 2);
  auto args = dome_job(program);
  args.erase(std::find(args.begin(), args.end(), "-q"));
  const ChildResult lenient = run_vcpost(with(args, {"-o", (work / "lenient.nc").string()}), logs);
  EXPECT_EQ(lenient.shell_status(), 0) << lenient.err;
  static const std::regex warning(
      R"(vcpost: warning: ([0-9]+) cutting points do not touch the model)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(lenient.err, m, warning)) << lenient.err;
  EXPECT_GT(std::stoi(m[1].str()), 100);
  const ChildResult strict =
      run_vcpost(with(args, {"--strict", "-o", (work / "strict.nc").string()}), logs);
  EXPECT_EQ(strict.shell_status(), 1) << strict.err;
  EXPECT_NE(strict.err.find("vcpost: error: warnings with --strict; nothing written"),
            std::string::npos);
  EXPECT_NE(strict.err.find("cutting points do not touch the model"), std::string::npos);
  EXPECT_FALSE(fs::exists(work / "strict.nc"));
}

}  // namespace
}  // namespace vcpost::test
