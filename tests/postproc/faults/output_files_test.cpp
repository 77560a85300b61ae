// Outputs never cost an input or another output (issue 18): every output
// of `vcpost post`/`report` must be a file other than the program, the
// model, the machine profile, the tools table and the other outputs,
// however it is named (relative, through a symbolic or a hard link); a device or FIFO is written in
// place, never replaced; a symbolic link writes its target; an existing
// output keeps its mode; a hard link is refused, not split. The real
// binary on the dome sample; inputs are hashed before and after.
#include <gtest/gtest.h>
#include <sys/sysmacros.h>

#include <regex>

#include "tests/postproc/faults/child_process.h"

namespace vcpost::test {
namespace {

namespace fs = std::filesystem;

const fs::path kSamples = fs::path(VCPOST_SOURCE_DIR) / "samples";
const std::string kVcpost = VCPOST_BINARY;

// Copies of the dome sample's inputs in `work` (so a failure here cannot
// damage the repository), and the job on them.
struct DomeJob {
  fs::path program, model, machine, tools;  // tools: given by the clashes that name it
  explicit DomeJob(const fs::path& work)
      : program(work / "in.nc"),
        model(work / "dome.step"),
        machine(work / "m.toml"),
        tools(work / "tools.toml") {
    fs::copy_file(kSamples / "dome_raster_a0_ae3.nc", program);
    fs::copy_file(kSamples / "dome.step", model);
    fs::copy_file(fs::path(VCPOST_SOURCE_DIR) / "machines/profiles/generic.toml", machine);
    std::ofstream(tools) << "[[tool]]\nnumber = 1\nshape = \"ball\"\ndiameter = 10.0\n";
  }
  std::vector<std::string> args(std::vector<std::string> extra,
                                const char* command = "post") const {
    std::vector<std::string> a{kVcpost,   command,        program.string(),
                               "--model", model.string(), "--tool",
                               "ball:10", "--vc",         "120",
                               "--ap",    "0.3",          "--ae",
                               "3",       "--machine",    machine.string()};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  }
  std::vector<std::uint64_t> hashes() const {
    return {file_hash(program), file_hash(model), file_hash(machine), file_hash(tools)};
  }
};

ChildResult run(std::vector<std::string> args, const Folder& logs) {
  ChildOptions o;
  o.argv = std::move(args);
  o.stdout_file = logs / "stdout.txt";
  o.stderr_file = logs / "stderr.txt";
  return run_child(o);
}

struct Clash {
  const char* name;
  // The arguments naming the outputs, given the job's files and the work folder.
  std::function<std::vector<std::string>(const DomeJob&, const fs::path&)> outputs;
  const char* message;  // expected in the one error line
};

void PrintTo(const Clash& c, std::ostream* out) { *out << c.name; }

class OutputClash : public ::testing::TestWithParam<Clash> {};

TEST_P(OutputClash, IsRefusedBeforeAnyWork) {
  // Each clash: exit 2, one line naming both files, no output written and
  // every input byte-identical.
  Folder work, logs;
  const DomeJob job(work.path());
  const auto outputs = GetParam().outputs(job, work.path());  // may make links
  const auto before = job.hashes();
  const auto listed = list_folder(work.path());
  const ChildResult r = run(job.args(outputs), logs);
  EXPECT_EQ(r.shell_status(), 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(GetParam().message), std::string::npos) << r.err;
  EXPECT_EQ(job.hashes(), before);
  EXPECT_EQ(list_folder(work.path()), listed);
}

INSTANTIATE_TEST_SUITE_P(
    Files, OutputClash,
    ::testing::Values(
        Clash{"SummaryIsTheProgram",
              [](const DomeJob& j, const fs::path& w) {
                return std::vector<std::string>{"-o", (w / "out.nc").string(), "--summary-json",
                                                j.program.string()};
              },
              "--summary-json '"},
        Clash{"OutputIsTheModel",
              [](const DomeJob& j, const fs::path&) {
                return std::vector<std::string>{"-o", j.model.string()};
              },
              "is the same file as the input --model"},
        Clash{"SummaryIsTheModelThroughALink",
              [](const DomeJob& j, const fs::path& w) {
                fs::create_symlink(j.model, w / "link.json");
                return std::vector<std::string>{"-o", (w / "out.nc").string(), "--summary-json",
                                                (w / "link.json").string()};
              },
              "is the same file as the input --model"},
        Clash{"ReportIsTheMachineProfile",
              [](const DomeJob& j, const fs::path& w) {
                fs::create_symlink(j.machine, w / "m.json");
                return std::vector<std::string>{"-o", (w / "out.nc").string(), "--report",
                                                (w / "m.json").string()};
              },
              "is the same file as the input --machine"},
        Clash{
            "OutputIsTheToolsTable",
            [](const DomeJob& j, const fs::path&) {
              return std::vector<std::string>{"--tools", j.tools.string(), "-o", j.tools.string()};
            },
            "is the same file as the input --tools"},
        Clash{"SummaryIsTheToolsTableThroughALink",
              [](const DomeJob& j, const fs::path& w) {
                fs::create_symlink("tools.toml", w / "t.json");
                return std::vector<std::string>{
                    "--tools",        j.tools.string(),       "-o", (w / "out.nc").string(),
                    "--summary-json", (w / "t.json").string()};
              },
              "is the same file as the input --tools"},
        Clash{"ReportIsTheToolsTableThroughAHardLink",
              [](const DomeJob& j, const fs::path& w) {
                fs::create_hard_link(j.tools, w / "t.html");
                return std::vector<std::string>{"--tools",  j.tools.string(),
                                                "-o",       (w / "out.nc").string(),
                                                "--report", (w / "t.html").string()};
              },
              "is the same file as the input --tools"},
        Clash{"SummaryIsTheOutput",
              [](const DomeJob&, const fs::path& w) {
                return std::vector<std::string>{"-o", (w / "out.nc").string(), "--summary-json",
                                                (w / "." / "out.nc").string()};
              },
              "is the same file as -o"},
        Clash{"ReportIsTheSummary",
              [](const DomeJob&, const fs::path& w) {
                return std::vector<std::string>{"-o",
                                                (w / "out.nc").string(),
                                                "--report",
                                                (w / "s.json").string(),
                                                "--summary-json",
                                                (w / "s.json").string()};
              },
              "is the same file as --summary-json"},
        Clash{"OutputIsAFolder",
              [](const DomeJob&, const fs::path& w) {
                return std::vector<std::string>{"-o", w.string()};
              },
              "it is a folder"}));

TEST(OutputFiles, ReportCommandOutputIsTheProgram) {
  Folder work, logs;
  const DomeJob job(work.path());
  fs::copy_file(job.program, work / "in.json");
  auto args = job.args({"-o", (work / "r.html").string()}, "report");
  args[2] = (work / "in.json").string();
  args.push_back("-o");
  args.push_back((work / "in.json").string());
  const auto before = file_hash(work / "in.json");
  const ChildResult r = run(args, logs);
  EXPECT_EQ(r.shell_status(), 2) << r.err;
  EXPECT_NE(r.err.find("is the same file as the input program"), std::string::npos) << r.err;
  EXPECT_EQ(file_hash(work / "in.json"), before);
}

TEST(OutputFiles, FifoIsWrittenInPlace) {
  // -o FIFO: the reader gets the whole program, and the FIFO is still a
  // FIFO afterwards (it used to be replaced by a regular file by the rename,
  // and its reader got nothing).
  Folder work, logs;
  const DomeJob job(work.path());
  const ChildResult plain = run(job.args({"-q", "-o", (work / "plain.nc").string()}), logs);
  ASSERT_EQ(plain.shell_status(), 0) << plain.err;
  const fs::path fifo = work / "fifo.nc";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(reader, 0);
  std::string got;
  const auto drain = [&] {
    char buffer[65536];
    for (ssize_t n; (n = ::read(reader, buffer, sizeof buffer)) > 0;) got.append(buffer, n);
  };
  ChildOptions o;
  o.argv = job.args({"-q", "-o", fifo.string()});
  o.stdout_file = logs / "stdout.txt";
  o.stderr_file = logs / "stderr.txt";
  o.while_running = [&](pid_t pid) {
    while (still_running(pid)) {
      drain();
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  };
  const ChildResult r = run_child(o);
  drain();
  ::close(reader);
  EXPECT_EQ(r.shell_status(), 0) << r.err;
  EXPECT_TRUE(fs::is_fifo(fs::symlink_status(fifo)));
  EXPECT_EQ(got, read_file(work / "plain.nc"));
  EXPECT_EQ(list_folder(work.path()),
            (std::vector<std::string>{"dome.step", "fifo.nc", "in.nc", "m.toml", "plain.nc",
                                      "tools.toml"}));
}

TEST(OutputFiles, CharacterDeviceStaysADevice) {
  // -o onto a character device (a private copy of /dev/null, made with
  // mknod: as root the rename used to turn /dev/null itself into a regular
  // file). Also given twice (-o and --summary-json): a device loses nothing.
  if (::geteuid() != 0) GTEST_SKIP() << "mknod of a character device needs root";
  Folder work, logs;
  const DomeJob job(work.path());
  const fs::path null = work / "null";
  ASSERT_EQ(::mknod(null.c_str(), S_IFCHR | 0666, ::makedev(1, 3)), 0);
  const ChildResult r =
      run(job.args({"-q", "-o", null.string(), "--summary-json", null.string()}), logs);
  EXPECT_EQ(r.shell_status(), 0) << r.err;
  struct stat info {};
  ASSERT_EQ(::stat(null.c_str(), &info), 0);
  EXPECT_TRUE(S_ISCHR(info.st_mode));
  EXPECT_EQ(list_folder(work.path()),
            (std::vector<std::string>{"dome.step", "in.nc", "m.toml", "null", "tools.toml"}));
}

TEST(OutputFiles, SymbolicLinkWritesItsTarget) {
  // -o LINK: the link stays a link, its target gets the program, and the
  // end-of-run lines say so.
  Folder work, logs;
  const DomeJob job(work.path());
  fs::create_directory(work / "real");
  std::ofstream(work / "real/out.nc") << "old\n";
  fs::create_symlink("real/out.nc", work / "out.nc");
  const ChildResult plain = run(job.args({"-q", "-o", (work / "plain.nc").string()}), logs);
  ASSERT_EQ(plain.shell_status(), 0) << plain.err;
  const ChildResult r = run(job.args({"-o", (work / "out.nc").string()}), logs);
  EXPECT_EQ(r.shell_status(), 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(work / "out.nc"));
  EXPECT_EQ(read_file(work / "real/out.nc"), read_file(work / "plain.nc"));
  EXPECT_NE(r.err.find("vcpost: '" + (work / "out.nc").string() +
                       "' is a symbolic link: wrote its target '" +
                       (work / "real/out.nc").string() + "'\n"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(list_folder(work / "real"), std::vector<std::string>{"out.nc"});
}

TEST(OutputFiles, DanglingLinkCreatesItsTarget) {
  Folder work, logs;
  const DomeJob job(work.path());
  fs::create_symlink("new.nc", work / "out.nc");
  const ChildResult r = run(job.args({"-q", "-o", (work / "out.nc").string()}), logs);
  EXPECT_EQ(r.shell_status(), 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(work / "out.nc"));
  EXPECT_GT(fs::file_size(work / "new.nc"), 1000u);
}

TEST(OutputFiles, ExistingOutputKeepsItsMode) {
  Folder work, logs;
  const DomeJob job(work.path());
  std::ofstream(work / "out.nc") << "old\n";
  fs::permissions(work / "out.nc", fs::perms::owner_read | fs::perms::owner_write |
                                       fs::perms::group_read | fs::perms::owner_exec);
  const ChildResult r = run(job.args({"-q", "-o", (work / "out.nc").string(), "--summary-json",
                                      (work / "s.json").string()}),
                            logs);
  EXPECT_EQ(r.shell_status(), 0) << r.err;
  EXPECT_EQ(fs::status(work / "out.nc").permissions(),
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                fs::perms::owner_exec);
  EXPECT_GT(fs::file_size(work / "out.nc"), 1000u);
}

TEST(OutputFiles, HardLinkIsRefusedNotSplit) {
  // out.nc has a second name: replacing it by rename would leave the other
  // name with the old bytes, silently. Refused (exit 2), both unchanged.
  Folder work, logs;
  const DomeJob job(work.path());
  std::ofstream(work / "out.nc") << "old\n";
  fs::create_hard_link(work / "out.nc", work / "other.nc");
  const ChildResult r = run(job.args({"-q", "-o", (work / "out.nc").string()}), logs);
  EXPECT_EQ(r.shell_status(), 2) << r.err;
  EXPECT_NE(r.err.find("it has 2 hard links"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(work / "out.nc"), "old\n");
  EXPECT_EQ(fs::hard_link_count(work / "other.nc"), 2u);
}

// `ARGUMENTS` as one shell word each ('...'; no test path holds a quote).
std::string shell_words(const std::vector<std::string>& args) {
  std::string line;
  for (const auto& a : args) line += (line.empty() ? "'" : " '") + a + "'";
  return line;
}

// The JSON summary without the one key that differs from run to run.
std::string without_run_time(const std::string& summary) {
  static const std::regex run_time("\n *\"run_time_s\": [0-9.e+-]+,");
  return std::regex_replace(summary, run_time, "");
}

TEST(OutputFiles, OwnStandardStreamsAreWrittenInPlace) {
  // /dev/stderr, /dev/stdout, /dev/fd/N and /proc/self/fd/N are links to
  // the process's own open file. `--summary-json /dev/stderr 2>>log`
  // followed them to the log and replaced it by rename (a new inode, its
  // first line gone); behind a pipe (`2>&1 | cat`, `-o /dev/stdout | wc`)
  // the link leads to "pipe:[...]" and the run failed, exit 2: "cannot
  // create a file in '/proc/self/fd'". Now the bytes go into the open
  // descriptor as the shell opened it: appended to the log, into the pipe.
  Folder work, logs;
  const DomeJob job(work.path());
  const fs::path out = work / "out.nc", summary = work / "s.json";
  const ChildResult plain =
      run(job.args({"-q", "-o", out.string(), "--summary-json", summary.string()}), logs);
  ASSERT_EQ(plain.shell_status(), 0) << plain.err;
  const std::string program = read_file(out), json = without_run_time(read_file(summary));
  ASSERT_GT(json.size(), 500u);
  const auto shell = [&](const std::string& line) {
    return run({"/bin/sh", "-c", "cd '" + work.path().string() + "' && " + line}, logs);
  };
  const fs::path log = work / "log";
  for (const std::string name : {"/dev/stderr", "/dev/fd/2", "/proc/self/fd/2"}) {
    std::ofstream(log) << "x\n";
    const auto inode = [&log] {
      struct stat info {};
      return ::stat(log.c_str(), &info) == 0 ? info.st_ino : 0;
    };
    const auto before = inode();
    const ChildResult r = shell(
        shell_words(job.args({"-q", "-o", out.string(), "--summary-json", name})) + " 2>>log");
    EXPECT_EQ(r.shell_status(), 0) << name << ": " << r.err;
    EXPECT_EQ(inode(), before) << name << ": the log was replaced";
    const std::string text = read_file(log);
    EXPECT_EQ(text.substr(0, 2), "x\n") << name;
    EXPECT_TRUE(without_run_time(text.substr(std::min<std::size_t>(2, text.size()))) == json)
        << name << ": the log holds " << text.size() << " bytes: " << text.substr(0, 40);
  }
  for (const std::string name : {"/dev/stderr", "/proc/self/fd/2"}) {
    fs::remove(work / "got");
    const ChildResult r =
        shell("{ " + shell_words(job.args({"-q", "-o", out.string(), "--summary-json", name})) +
              " 2>&1; echo $? >status; } | cat >got");
    EXPECT_EQ(r.shell_status(), 0) << name << ": " << r.err;
    EXPECT_EQ(read_file(work / "status"), "0\n")
        << name << ": " << read_file(work / "got").substr(0, 300);
    EXPECT_TRUE(without_run_time(read_file(work / "got")) == json)
        << name << ": " << read_file(work / "got").substr(0, 300);
  }
  for (const std::string name : {"/dev/stdout", "/dev/fd/1"}) {
    fs::remove(work / "got");
    const ChildResult r = shell("{ " + shell_words(job.args({"-q", "-o", name})) +
                                " 2>err; echo $? >status; } | cat >got");
    EXPECT_EQ(r.shell_status(), 0) << name << ": " << r.err;
    EXPECT_EQ(read_file(work / "status"), "0\n") << name << ": " << read_file(work / "err");
    EXPECT_TRUE(read_file(work / "got") == program)
        << name << ": " << read_file(work / "got").size() << " bytes";
  }
  // Standard input is no output (it replaced the file behind it): refused.
  std::ofstream(log) << "x\n";
  const ChildResult r = shell(shell_words(job.args({"-q", "-o", "/dev/stdin"})) + " <log");
  EXPECT_EQ(r.shell_status(), 2) << r.err;
  EXPECT_EQ(r.err, "vcpost: error: cannot write '/dev/stdin': it is open for reading only\n");
  EXPECT_EQ(read_file(log), "x\n");
}

}  // namespace
}  // namespace vcpost::test
