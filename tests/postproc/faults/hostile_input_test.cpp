// Hostile input against the real `vcpost` binary (issue 18): binary and
// endless input, NaN options, absurd profiles, programs without motion or
// end, lines run more than once, failing standard output, and the words of
// the messages. Each case has a time limit (a hang fails, it does not stop
// the suite) and, where memory was the problem, an address-space limit.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <regex>
#include <thread>

#include "tests/postproc/faults/child_process.h"

namespace vcpost::test {
namespace {

namespace fs = std::filesystem;

const fs::path kSamples = fs::path(VCPOST_SOURCE_DIR) / "samples";
const std::string kVcpost = VCPOST_BINARY;
const std::string kDome = (kSamples / "dome_raster_a0_ae3.nc").string();

std::vector<std::string> dome_job(const std::string& program, std::vector<std::string> extra) {
  std::vector<std::string> a{
      kVcpost,  "post",    program, "--model", (kSamples / "dome.step").string(),
      "--tool", "ball:10", "--vc",  "120",     "--ap",
      "0.3",    "--ae",    "3"};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

ChildResult run(std::vector<std::string> args, const Folder& logs,
                const std::function<void(ChildOptions&)>& adjust = {}) {
  ChildOptions o;
  o.argv = std::move(args);
  o.stdout_file = logs / "stdout.txt";
  o.stderr_file = logs / "stderr.txt";
  o.timeout_s = 60;
  if (adjust) adjust(o);
  return run_child(o);
}

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// --- crashes and hangs -----------------------------------------------------

// 1 GB of address space for the child; none under AddressSanitizer, whose
// shadow memory reserves terabytes of it (the timeout still bounds the run).
#if defined(__SANITIZE_ADDRESS__)
const std::optional<rlim_t> kAddressSpaceLimit;
#else
const std::optional<rlim_t> kAddressSpaceLimit = rlim_t{1} << 30;
#endif

TEST(HostileInput, NulFileStopsAtTheFirstNulInBoundedMemory) {
  // 100 MB of NUL bytes (sparse): `verify z z` took 11 GB, `post` and
  // `moves` read it all to report a "line of 2147483648 bytes". Now each
  // stops at byte 1 with its position, under a 1 GB address-space limit.
  Folder work, logs;
  const fs::path z = work / "z.nc";
  { std::ofstream out(z, std::ios::binary); }
  fs::resize_file(z, 100u << 20);
  const auto limited = [](ChildOptions& o) {
    o.memory_limit = kAddressSpaceLimit;
    o.timeout_s = 20;
  };
  for (const auto& args : {std::vector<std::string>{kVcpost, "verify", z.string(), z.string()},
                           std::vector<std::string>{kVcpost, "moves", z.string()},
                           dome_job(z.string(), {"-o", "-"})}) {
    const ChildResult r = run(args, logs, limited);
    EXPECT_EQ(r.shell_status(), 2) << args[1] << ": " << r.err;
    EXPECT_NE(r.err.find(z.string() + ":1:1: error[E1002]: NUL byte: this is no text program"),
              std::string::npos)
        << args[1] << ": " << r.err;
  }
}

// Peak resident size of a run that must not hold its input: 100 MB (the
// runs take 22-34 MB), 400 MB under AddressSanitizer (its shadow memory).
#if defined(__SANITIZE_ADDRESS__)
constexpr long kPeakRssBoundKb = 400'000;
#else
constexpr long kPeakRssBoundKb = 100'000;
#endif

TEST(HostileInput, EndlessFirstLineIsRefusedInBoundedMemory) {
  // A program whose first line is 200 MB long, no newline, under a line
  // limit of 65,536 bytes: the kind was sniffed from the whole line (a
  // copy of it as a word, 460 MB resident for `post`, `moves`), and
  // `verify` split it into tokens (660 MB for letters, 12.9 GB for words).
  // Now each refuses it at the limit, having read no further than that:
  // the peak resident size stays far below the file's size.
  Folder work, logs;
  const fs::path p = work / "long.nc";
  for (const std::string piece : {"G1 X1 Y2 Z3 ", "X"}) {
    {
      std::ofstream out(p, std::ios::binary);
      const std::string block = [&] {
        std::string b;
        while (b.size() < (1u << 20)) b += piece;
        return b;
      }();
      for (std::size_t written = 0; written < 200'000'000; written += block.size()) out << block;
    }
    const auto limited = [](ChildOptions& o) {
      o.memory_limit = kAddressSpaceLimit;
      o.timeout_s = 30;
    };
    for (const auto& args : {std::vector<std::string>{kVcpost, "verify", p.string(), p.string()},
                             std::vector<std::string>{kVcpost, "moves", p.string()},
                             dome_job(p.string(), {"-o", "-"})}) {
      const ChildResult r = run(args, logs, limited);
      EXPECT_EQ(r.shell_status(), 2) << args[1] << " '" << piece << "': " << r.err;
      EXPECT_EQ(r.err, "vcpost: error: " + p.string() +
                           ":1:1: error[E1006]: line longer than 65536 bytes, the reader's limit\n")
          << args[1] << " '" << piece << "'";
      EXPECT_LT(r.peak_rss_kb, kPeakRssBoundKb) << args[1] << " '" << piece << "'";
      std::printf("%s on a 200 MB line of '%s': peak RSS %ld KB, %.2f s\n", args[1].c_str(),
                  piece.c_str(), r.peak_rss_kb, r.seconds);
    }
  }
}

TEST(HostileInput, NulAfterTextGivesItsLineAndColumn) {
  Folder work, logs;
  const fs::path p = work / "p.nc";
  write(p, "G21 G90\nG0 X1\nG1 X2 F100\nM2 " + std::string(1, '\0') + "\n");
  const ChildResult r = run({kVcpost, "moves", p.string()}, logs);
  EXPECT_EQ(r.shell_status(), 2);
  EXPECT_EQ(r.err, "vcpost: error: " + p.string() +
                       ":4:4: error[E1002]: NUL byte: this is no text program (binary data?); "
                       "nothing read past it\n");
}

TEST(HostileInput, RandomBytesAreRefusedAtOnce) {
  // /dev/urandom as the program, and on standard input: no answer in 60 s
  // and memory growing to an OOM kill; now refused at its first NUL byte.
  Folder logs;
  for (const bool on_stdin : {false, true}) {
    const ChildResult r =
        run(dome_job(on_stdin ? "-" : "/dev/urandom", {"-o", "-"}), logs, [&](ChildOptions& o) {
          if (on_stdin) o.stdin_file = "/dev/urandom";
          o.memory_limit = kAddressSpaceLimit;
          o.timeout_s = 20;
        });
    EXPECT_EQ(r.shell_status(), 2) << r.err;
    EXPECT_NE(r.err.find("NUL byte: this is no text program"), std::string::npos) << r.err;
    EXPECT_LT(r.seconds, 10);
  }
}

TEST(HostileInput, StandardInputIsStillRead) {
  // The dome program on standard input posts as from the file.
  Folder work, logs;
  const ChildResult file = run(dome_job(kDome, {"-q", "-o", "-"}), logs);
  ASSERT_EQ(file.shell_status(), 0) << file.err;
  const ChildResult piped =
      run(dome_job("-", {"-q", "-o", "-"}), logs, [](ChildOptions& o) { o.stdin_file = kDome; });
  EXPECT_EQ(piped.shell_status(), 0) << piped.err;
  EXPECT_EQ(piped.out, file.out);
}

TEST(HostileInput, EndlessLineOnStandardInputIsCopiedNoFurther) {
  // Standard input is copied into a temporary file: an endless line (no
  // newline, no NUL) was copied until the disk was full. Now the copy stops
  // once the line passes the readers' limit, which then refuses it. The
  // writer gives up after 1 GB; it is stopped long before by the broken pipe.
  Folder work, logs;
  const fs::path fifo = work / "stdin";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::uint64_t written = 0;
  std::thread writer([&] {
    sigset_t pipe_signal;
    sigemptyset(&pipe_signal);
    sigaddset(&pipe_signal, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipe_signal, nullptr);  // EPIPE instead of the signal
    const int fd = ::open(fifo.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) return;
    const std::string block(1 << 16, 'X');
    while (written < (std::uint64_t{1} << 30)) {
      const ssize_t put = ::write(fd, block.data(), block.size());
      if (put <= 0) break;
      written += static_cast<std::uint64_t>(put);
    }
    ::close(fd);
  });
  const ChildResult r = run({kVcpost, "moves", "-"}, logs, [&](ChildOptions& o) {
    o.stdin_file = fifo;
    o.timeout_s = 60;
  });
  writer.join();
  EXPECT_EQ(r.shell_status(), 2) << r.err;
  EXPECT_EQ(r.err,
            "vcpost: error: <stdin>:1:1: error[E1006]: line longer than 65536 bytes, the "
            "reader's limit\n");
  EXPECT_LT(written, std::uint64_t{16} << 20) << "the endless line was read on";
}

TEST(HostileInput, HelpEndsQuietlyWhenTheReaderLeaves) {
  // `vcpost post --help | head -1` printed "interrupted by SIGPIPE; no
  // output written" after the lines head showed. The reader is gone before
  // the help is written here, so the write always meets the closed pipe.
  Folder logs;
  int fds[2];
  ASSERT_EQ(::pipe2(fds, O_CLOEXEC), 0);
  ::close(fds[0]);
  const ChildResult r =
      run({kVcpost, "post", "--help"}, logs, [&](ChildOptions& o) { o.stdout_fd = fds[1]; });
  ::close(fds[1]);
  EXPECT_FALSE(r.exited);
  EXPECT_EQ(r.signal, SIGPIPE);
  EXPECT_EQ(r.err, "");
}

TEST(HostileInput, FifoModelIsRefusedNotWaitedFor) {
  // A FIFO as the model blocked forever (its format was sniffed by one
  // open, then read by a second one). Now refused with a message.
  Folder work, logs;
  const fs::path fifo = work / "model.stl";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  auto args = dome_job(kDome, {"-o", (work / "out.nc").string()});
  args[4] = fifo.string();
  const ChildResult r = run(args, logs, [](ChildOptions& o) { o.timeout_s = 20; });
  EXPECT_EQ(r.shell_status(), 2) << r.err;
  EXPECT_NE(r.err.find("is not a regular file (a FIFO or a device)"), std::string::npos) << r.err;
}

TEST(HostileInput, SpacingHasAFloor) {
  // --spacing 1e-6 was OOM-killed at 24 GB, 1e-300 ended in "time is not
  // finite" (exit 3): below the documented floor of 0.001 mm it is a usage
  // error; at the floor the job runs.
  Folder work, logs;
  for (const char* spacing : {"1e-6", "1e-300", "0.0009"}) {
    const ChildResult r = run(dome_job(kDome, {"-q", "--spacing", spacing, "-o", "-"}), logs);
    EXPECT_EQ(r.shell_status(), 2) << spacing << ": " << r.err;
    EXPECT_NE(r.err.find("--spacing: must be between 0.001 and 1000000, got"), std::string::npos)
        << r.err;
  }
}

TEST(HostileInput, LinesRunTwiceArePosted) {
  // A subroutine called twice (o100 sub / o100 call): "internal error:
  // write_patched: patch offset 18446744073709551456" (exit 3). Now posted,
  // verified, and the summary counts the lines run more than once.
  Folder work, logs;
  // Header: the dome program's first 6 lines; body: its next 200 (the
  // rapid down and the first passes), then back up.
  std::istringstream lines(read_file(kDome));
  std::string header, body, line;
  for (int n = 1; n <= 206 && std::getline(lines, line); ++n)
    (n <= 6 ? header : body) += line + "\n";
  const fs::path p = work / "sub.ngc";
  write(p, header + "o100 sub\n" + body + "G0 Z50\no100 endsub\no100 call\no100 call\nM5\nM30\n");
  const fs::path out = work / "out.ngc";
  auto args =
      dome_job(p.string(), {"-o", out.string(), "--summary-json", (work / "s.json").string()});
  const ChildResult r = run(args, logs);
  ASSERT_EQ(r.shell_status(), 0) << r.err;
  EXPECT_NE(r.err.find("lines run more than once (subroutines, loops): each has the lowest S"),
            std::string::npos)
      << r.err;
  EXPECT_NE(read_file(work / "s.json").find("\"repeated_lines\": "), std::string::npos);
  const ChildResult v = run({kVcpost, "verify", p.string(), out.string()}, logs);
  EXPECT_EQ(v.shell_status(), 0) << v.err << v.out;
}

// --- wrong results ---------------------------------------------------------

TEST(HostileInput, NonFiniteNumbersAreUsageErrors) {
  Folder work, logs;
  const std::vector<std::vector<std::string>> cases = {
      dome_job(kDome, {"--vc", "nan", "-o", "-"}),
      dome_job(kDome, {"--ap", "inf", "-o", "-"}),
      dome_job(kDome, {"--ae", "nan", "-o", "-"}),
      dome_job(kDome, {"--spacing", "nan", "-o", "-"}),
      dome_job(kDome, {"--contact-tolerance=-inf", "-o", "-"}),
      dome_job(kDome, {"--adjust-feed", "--fz", "nan", "-o", "-"}),
      {kVcpost, "verify", kDome, kDome, "--tolerance", "nan"},
      {kVcpost, "moves", "--time", "--rapid-rate", "nan", kDome},
      {kVcpost, "report", kDome, "--model", (kSamples / "dome.step").string(), "--tool", "ball:10",
       "--vc", "NaN", "--ap", "0.3", "-o", "-"}};
  for (const auto& args : cases) {
    const ChildResult r = run(args, logs);
    EXPECT_EQ(r.shell_status(), 2) << joined(args) << ": " << r.err;
    EXPECT_NE(r.err.find("is not a"), std::string::npos) << r.err;  // "finite number" or "number"
    EXPECT_EQ(r.out, "");
  }
}

TEST(HostileInput, RangeErrorsAreShort) {
  // "Value 0 not in range 0.000000 to 179769313486231570..." before.
  Folder logs;
  const ChildResult r = run(dome_job(kDome, {"--vc", "0", "-o", "-"}), logs);
  EXPECT_EQ(r.shell_status(), 2);
  EXPECT_NE(r.err.find("--vc '0': must be > 0 m/min"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("1797693"), std::string::npos) << r.err;
}

TEST(HostileInput, AbsurdProfileValuesAreRefused) {
  // block_time_s = 1e300 printed "-2147483648 % after" and NaN in the JSON.
  Folder work, logs;
  std::string profile = read_file(fs::path(VCPOST_SOURCE_DIR) / "machines/profiles/generic.toml");
  const std::regex key(R"(block_time_s *= *[0-9.eE+-]+)");
  ASSERT_TRUE(std::regex_search(profile, key));
  write(work / "m.toml", std::regex_replace(profile, key, "block_time_s = 1e300"));
  const ChildResult r =
      run(dome_job(kDome, {"--machine", (work / "m.toml").string(), "-o", "-"}), logs);
  EXPECT_EQ(r.shell_status(), 2) << r.err;
  EXPECT_NE(r.err.find("block_time_s"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("must be at most 10 s"), std::string::npos) << r.err;
}

TEST(HostileInput, ProfileRatesHaveFloors) {
  // rapid_mm_per_min = 1e-300 and acceleration_rpm_per_s = 1e-300 were
  // accepted: every G0 then lasted 1e303 s (9.1e+303 in the JSON). Each
  // now stops the run at its file:line:col with E5005.
  Folder work, logs;
  const std::string profile =
      read_file(fs::path(VCPOST_SOURCE_DIR) / "machines/profiles/generic.toml");
  for (const auto& [key, floor] :
       {std::pair<std::string, std::string>{"rapid_mm_per_min", "must be at least 10 mm/min"},
        {"acceleration_rpm_per_s", "must be at least 1 rpm/s"},
        // n_min_rpm = 1e-300 let a slow point be written S0 (spindle off).
        {"n_min_rpm", "must be at least 1 rpm"},
        {"s_resolution_rpm", "must be at least 0.001 rpm"}}) {
    SCOPED_TRACE(key);
    const std::regex assignment(key + R"( *= *[0-9.eE+-]+)");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(profile, m, assignment));
    const std::string text = std::regex_replace(profile, assignment, key + " = 1e-300");
    const std::size_t line = 1 + static_cast<std::size_t>(std::count(
                                     profile.begin(), profile.begin() + m.position(0), '\n'));
    const fs::path file = work / "m.toml";
    write(file, text);
    const ChildResult r =
        run(dome_job(kDome, {"--machine", file.string(), "-o", (work / "out.nc").string()}), logs);
    EXPECT_EQ(r.shell_status(), 2) << r.err;
    const std::string table = key == "rapid_mm_per_min" ? "feed." : "spindle.";
    EXPECT_EQ(r.err, "vcpost: error: " + file.string() + ":" + std::to_string(line) + ":" +
                         std::to_string(key.size() + 4) + ": error[E5005]: '" + table + key + "' " +
                         floor + "\n");
    EXPECT_FALSE(fs::exists(work / "out.nc"));
  }
}

TEST(HostileInput, ModelFiveMillimetresHigherIsAnError) {
  // Every Z of the program 5 mm down (the model "5 mm higher"): no point
  // touches, nearly all gouge. Exit 0 with rewritten S before; now exit 2
  // with the diagnosis, and no output file.
  Folder work, logs;
  std::string text = read_file(kDome);
  std::string shifted;
  static const std::regex z_word(R"(Z(-?[0-9]+\.?[0-9]*))");
  auto last = text.cbegin();
  for (std::sregex_iterator m(text.begin(), text.end(), z_word), end; m != end; ++m) {
    shifted.append(last, (*m)[0].first);
    char number[32];
    std::snprintf(number, sizeof number, "Z%.3f", std::stod((*m)[1].str()) - 5);
    shifted += number;
    last = (*m)[0].second;
  }
  shifted.append(last, text.cend());
  write(work / "low.nc", shifted);
  const ChildResult r =
      run(dome_job((work / "low.nc").string(), {"-o", (work / "out.nc").string()}), logs);
  EXPECT_EQ(r.shell_status(), 2) << r.err;
  EXPECT_NE(r.err.find("the toolpath gouges the model at "), std::string::npos) << r.err;
  // The diagnosis of the sections: the gouge depths (a Z shift of 5 mm is
  // at most 5 mm deep along the dome's normals, plus the chord errors of
  // the CAM and of the mesh, 0.025 mm here) and, as no one offset
  // dominates on a dome, a word that says so.
  static const std::regex depths(R"(; gouge depth min [0-9.]+, median [0-9.]+, max ([0-9.]+) mm)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.err, m, depths)) << r.err;
  EXPECT_LE(std::stod(m[1].str()), 5.05) << r.err;
  EXPECT_GT(std::stod(m[1].str()), 4.0) << r.err;
  EXPECT_NE(r.err.find("no one offset dominates"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(work / "out.nc"));
}

// A plane at Z=0 (an ASCII STL, 100 mm square) and a raster inside it.
void write_plane_job(const fs::path& work, double z_tip) {
  write(work / "plane.stl",
        "solid plane\n"
        " facet normal 0 0 1\n  outer loop\n   vertex -50 -50 0\n   vertex 50 -50 0\n"
        "   vertex 50 50 0\n  endloop\n endfacet\n"
        " facet normal 0 0 1\n  outer loop\n   vertex -50 -50 0\n   vertex 50 50 0\n"
        "   vertex -50 50 0\n  endloop\n endfacet\n"
        "endsolid plane\n");
  char z[32];
  std::snprintf(z, sizeof z, "Z%.3f", z_tip);
  write(work / "plane.nc", std::string("%\nG21 G90 G17\nT1 M6\nS10000 M3\nG0 X-20 Y-20 ") + z +
                               "\nG1 X20 F500\nG1 Y-10\nG1 X-20\nG1 Y0\nG1 X20\nG1 Y10\n"
                               "G1 X-20\nM5\nM30\n%\n");
}

TEST(HostileInput, BinaryStlCountBelowItsRecordsIsAnInputError) {
  // The plane as a binary STL whose header announces 1 triangle of its 2:
  // refused with E4609, which had no row in the code table, so the run
  // ended as an internal error (exit 3) and `vcpost explain E4609` knew
  // nothing of it. Now a documented input error: exit 2.
  Folder work, logs;
  write_plane_job(work.path(), 0.0);
  std::string stl(80, ' ');
  const auto put = [&stl](const auto& value) {
    stl.append(reinterpret_cast<const char*>(&value), sizeof value);
  };
  put(std::uint32_t{1});
  for (const auto& t : {std::array<float, 9>{-50, -50, 0, 50, -50, 0, 50, 50, 0},
                        std::array<float, 9>{-50, -50, 0, 50, 50, 0, -50, 50, 0}}) {
    for (float v : {0.0f, 0.0f, 1.0f}) put(v);
    for (float v : t) put(v);
    put(std::uint16_t{0});
  }
  ASSERT_EQ(stl.size(), 84u + 2 * 50);
  const fs::path half = work / "half.stl";
  write(half, stl);
  const ChildResult r =
      run({kVcpost, "post", (work / "plane.nc").string(), "--model", half.string(), "--tool",
           "ball:10", "--vc", "120", "--ap", "0.3", "-o", (work / "out.nc").string()},
          logs);
  EXPECT_EQ(r.shell_status(), 2) << r.err;
  EXPECT_EQ(r.err.substr(0, r.err.find('\n') + 1),
            "vcpost: error: " + half.string() +
                ": offset 134: error[E4609]: binary STL header announces 1 triangles but the "
                "file holds 2 whole triangle records; the count is wrong (a damaged or "
                "concatenated file): export the model again\n");
  EXPECT_FALSE(fs::exists(work / "out.nc"));
  const ChildResult explain = run({kVcpost, "explain", "E4609"}, logs);
  EXPECT_EQ(explain.shell_status(), 0) << explain.err;
  EXPECT_NE(explain.out.find("stl_count_mismatch"), std::string::npos) << explain.out;
}

TEST(HostileInput, MismatchErrorGivesTheSectionsDiagnosis) {
  // The gross-mismatch error words the sections' own diagnosis (issue 15),
  // as the end-of-run lines do, not a list of its own. A D10 ball whose tip
  // runs 1 mm below a plane gouges 1.000 mm everywhere: the dominant offset
  // is -1 mm (negative stock to leave, or a larger tool). The same program
  // read as ball centres (--cl-point center) sits R = 5 mm into the plane:
  // the tool tip read as the centre.
  Folder work, logs;
  write_plane_job(work.path(), -1.0);
  const auto job = [&](std::vector<std::string> extra) {
    std::vector<std::string> a{kVcpost,
                               "post",
                               (work / "plane.nc").string(),
                               "--model",
                               (work / "plane.stl").string(),
                               "--tool",
                               "ball:10",
                               "--vc",
                               "120",
                               "--ap",
                               "0.3",
                               "--ae",
                               "3",
                               "-o",
                               (work / "out.nc").string()};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  const ChildResult below = run(job({}), logs);
  EXPECT_EQ(below.shell_status(), 2) << below.err;
  EXPECT_NE(below.err.find("gouge depth min 1.000, median 1.000, max 1.000 mm"), std::string::npos)
      << below.err;
  EXPECT_NE(below.err.find("100 % of the points near the model sit 1.000 mm into it: likely "
                           "negative stock to leave in the CAM"),
            std::string::npos)
      << below.err;
  EXPECT_EQ(below.err.find("no one offset dominates"), std::string::npos) << below.err;
  EXPECT_EQ(std::count(below.err.begin(), below.err.end(), '\n'), 1) << below.err;
  EXPECT_FALSE(fs::exists(work / "out.nc"));

  write_plane_job(work.path(), 0.0);
  const ChildResult center = run(job({"--cl-point", "center"}), logs);
  EXPECT_EQ(center.shell_status(), 2) << center.err;
  EXPECT_NE(center.err.find("gouge depth min 5.000, median 5.000, max 5.000 mm"), std::string::npos)
      << center.err;
  EXPECT_NE(center.err.find("sit 5.000 mm into it: likely the offset is minus the tool radius: "
                            "the program's points are likely the tool tip (try --cl-point tip)"),
            std::string::npos)
      << center.err;
  EXPECT_FALSE(fs::exists(work / "out.nc"));
  // Posted as written (tip on the plane), the same job touches everywhere.
  const ChildResult right = run(job({"-q"}), logs);
  EXPECT_EQ(right.shell_status(), 0) << right.err;
}

std::vector<std::string> wavy_job(const std::string& model, std::vector<std::string> extra) {
  std::vector<std::string> a{kVcpost,   "post", (kSamples / "wavy_raster_a0_ae2.nc").string(),
                             "--model", model,  "--vc",
                             "120",     "--ap", "0.3"};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

TEST(HostileInput, MismatchesThatTouchALittleAreErrors) {
  // The rule was "touching at 1 % of all points or fewer and gouging at
  // half": a D30 ball on the D10 raster touches at 108 of 8,704 points
  // (1.2 %) and gouges at 8,596; the wavy model labelled INCH (its numbers
  // are mm: 25.4 times too large) is gouged at 2,918 points, touched at
  // none, and missed at 5,786. Both posted with exit 0 and rewritten S.
  Folder work, logs;
  const fs::path out = work / "out.nc";
  const ChildResult ball30 = run(
      wavy_job((kSamples / "wavy.step").string(), {"--tool", "ball:30", "-o", out.string()}), logs);
  EXPECT_EQ(ball30.shell_status(), 2) << ball30.err;
  EXPECT_EQ(ball30.err.rfind("vcpost: error: the toolpath gouges the model at 8596 of 8704 points "
                             "and touches it at only 108: the program does not match the model; "
                             "gouge depth min 0.010, median 0.280, max 0.819 mm (8596 points)",
                             0),
            0u)
      << ball30.err;
  EXPECT_FALSE(fs::exists(out));

  std::string step = read_file(kSamples / "wavy.step");
  const std::string mm = "#213 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );\n";
  ASSERT_NE(step.find(mm), std::string::npos);
  step.replace(step.find(mm), mm.size(),
               "#213 = ( CONVERSION_BASED_UNIT('INCH',#900) LENGTH_UNIT() NAMED_UNIT(#901) );\n"
               "#900 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#902);\n"
               "#901 = DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.);\n"
               "#902 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );\n");
  write(work / "inch.step", step);
  const ChildResult inch = run(wavy_job((work / "inch.step").string(), {"-o", out.string()}), logs);
  EXPECT_EQ(inch.shell_status(), 2) << inch.err;
  EXPECT_EQ(inch.err,
            "vcpost: error: the toolpath gouges the model at 2918 of 8704 points and touches it "
            "at only 0: the program does not match the model; gouge depth min 3.211, median "
            "13.348, max 19.988 mm (2918 points); no one offset dominates (depths that vary with "
            "the surface's slope: a shifted work offset, other units or another tool diameter)\n");
  EXPECT_FALSE(fs::exists(out));
}

TEST(HostileInput, SectionThatNeverTouchesKeepsItsSpeed) {
  // The D10 ball's tip 0.5 mm into the dome's pole along 2 mm (a few
  // gouging points, too few to call the program a mismatch), the rest of
  // the path in the air: no point touches, so no cutting speed is kept and
  // the section keeps its S (it was posted: S rewritten from the gouges).
  Folder work, logs;
  std::string text =
      "%\n(T1 D=10. CR=5. - ball end mill)\nG21 G90 G17 G94\nT1 M6\nS4800 M3\nG0 X-1 Y0 Z50\n"
      "G1 Z39.5 F1000\nX1\nZ60\n";
  for (int i = 0; i < 20; ++i) text += "X-60 Y" + std::to_string(i) + "\nX60\n";
  text += "M30\n%\n";
  write(work / "dip.nc", text);
  const fs::path out = work / "out.nc";
  const fs::path summary = work / "s.json";
  const ChildResult r = run(dome_job((work / "dip.nc").string(),
                                     {"-o", out.string(), "--summary-json", summary.string()}),
                            logs);
  EXPECT_EQ(r.shell_status(), 0) << r.err;
  EXPECT_EQ(r.err.rfind("vcpost: 9568 points, 0 S words", 0), 0u) << r.err;
  EXPECT_EQ(read_file(out), text) << r.err;
  EXPECT_NE(read_file(summary).find("\"reason\": \"the path never touches the model: speed kept\""),
            std::string::npos)
      << read_file(summary);
}

TEST(HostileInput, ManyAirMovesAreNoMismatch) {
  // The dome raster with 40 passes of 120 mm in the air after it (about
  // 9,600 points lifted or far from the model, more than the raster's
  // 6,967) and a short gouge: posted, a warning, not an error.
  Folder work, logs;
  std::string text = read_file(kDome);
  std::string air = "G1 Z60 F1000\n";
  for (int i = 0; i < 20; ++i) air += "X-60 Y" + std::to_string(i) + "\nX60\n";
  air += "G1 X-1 Y0 Z39.9\nX1\nZ60\n";
  const std::size_t end = text.rfind("M30");
  ASSERT_NE(end, std::string::npos);
  text.insert(end, air);
  write(work / "air.nc", text);
  const ChildResult r = run(dome_job((work / "air.nc").string(), {"-o", "-"}), logs);
  EXPECT_EQ(r.shell_status(), 0) << r.err;
  EXPECT_NE(r.err.find("points gouge the model"), std::string::npos) << r.err;
}

TEST(HostileInput, ProgramWithoutMotionIsRefusedWithoutEndWarned) {
  Folder work, logs;
  write(work / "empty.nc", "");
  write(work / "comments.nc", "(only a comment)\n; and another\n");
  for (const char* name : {"empty.nc", "comments.nc"}) {
    const ChildResult r = run(dome_job((work / name).string(), {"-o", "-"}), logs);
    EXPECT_EQ(r.shell_status(), 2) << name << ": " << r.err;
    EXPECT_NE(r.err.find("the program has no motion"), std::string::npos) << r.err;
  }
  // The dome program cut in the middle of a number (two decimals after the
  // last point of its first half): posted, with a warning.
  std::string text = read_file(kDome);
  text.resize(text.find_last_of('.', text.size() / 2) + 3);
  write(work / "cut.nc", text);
  const ChildResult r = run(dome_job((work / "cut.nc").string(), {"-o", "-"}), logs);
  EXPECT_EQ(r.shell_status(), 0) << r.err;
  EXPECT_NE(r.err.find("vcpost: warning: the program ends without M2, M30 or a closing '%'"),
            std::string::npos)
      << r.err;
}

TEST(HostileInput, CannedCycleOfMillionsOfPecksIsRefusedInBoundedMemory) {
  // A G83 with 0.0001 mm pecks down 10 mm, repeated 100 times: 30 M moves
  // in one block, all held at once (gigabytes, then an OOM kill or
  // bad_alloc). Now refused before expanding, under a 1 GB address space.
  Folder work, logs;
  write(work / "pecks.ngc",
        "G21 G90 G17 G94\nF300 S2000 M3\nG0 X0 Y0 Z10\n"
        "G91 G83 X1 Y0 Z-10 R2 Q0.0001 L100\nG90 G80\nM2\n");
  const std::string where = (work / "pecks.ngc").string() + ":4:";
  for (const auto& args :
       {std::vector<std::string>{kVcpost, "moves", (work / "pecks.ngc").string()},
        dome_job((work / "pecks.ngc").string(), {"-o", "-"})}) {
    const ChildResult r = run(args, logs, [](ChildOptions& o) {
      o.memory_limit = kAddressSpaceLimit;
      o.timeout_s = 20;
    });
    EXPECT_EQ(r.shell_status(), 2) << args[1] << ": " << r.err;
    EXPECT_NE(r.err.find(where), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("error[E1308]: canned cycle makes more than 1000000 moves in one block"),
              std::string::npos)
        << args[1] << ": " << r.err;
  }
  // The same cycle with 0.1 mm pecks (300 moves a hole) still reads.
  write(work / "real.ngc",
        "G21 G90 G17 G94\nF300 S2000 M3\nG0 X0 Y0 Z10\n"
        "G91 G83 X1 Y0 Z-10 R2 Q0.1 L100\nG90 G80\nM2\n");
  const ChildResult ok = run({kVcpost, "moves", (work / "real.ngc").string()}, logs);
  EXPECT_EQ(ok.shell_status(), 0) << ok.err;
}

TEST(HostileInput, FailingStandardOutputIsExit2) {
  // `> /dev/full`: exit 0 before for all of these; the help promises 2.
  Folder logs;
  const std::vector<std::vector<std::string>> cases = {
      {kVcpost, "moves", kDome},
      {kVcpost, "verify", "--changes", kDome, kDome},
      {kVcpost, "deff", "--tool", "ball:10", "--ap", "1", "--ae", "1", "--tilt", "25", "--azimuth",
       "35", "--sweep", "feed-angle=0:360:15"},
      {kVcpost, "machines", "list"}};
  for (const auto& args : cases) {
    const ChildResult ok = run(args, logs);
    ASSERT_EQ(ok.shell_status(), 0) << joined(args) << ": " << ok.err;
    ASSERT_FALSE(ok.out.empty()) << joined(args);
    const ChildResult r = run(args, logs, [](ChildOptions& o) { o.stdout_file = "/dev/full"; });
    EXPECT_EQ(r.shell_status(), 2) << joined(args) << ": " << r.err;
    EXPECT_NE(r.err.find("cannot write to standard output: No space left on device"),
              std::string::npos)
        << r.err;
  }
}

// --- messages --------------------------------------------------------------

TEST(HostileInput, ProgramErrorsNameTheFile) {
  // "vcpost: error: :4:21: ..." before.
  Folder work, logs;
  write(work / "bad.nc", "G21 G90\nS8000 M3\nG0 X0 Y0 Z30\nG1 X1 Y1 Z20 F1000 G2 Q\nM30\n");
  for (const char* command : {"post", "report"}) {
    auto args = dome_job((work / "bad.nc").string(), {"-o", "-"});
    args[1] = command;
    if (std::string(command) == "report") args.back() = (work / "r.json").string();
    const ChildResult r = run(args, logs);
    EXPECT_EQ(r.shell_status(), 2) << r.err;
    EXPECT_EQ(r.err.rfind("vcpost: error: " + (work / "bad.nc").string() + ":4:", 0), 0u)
        << command << ": " << r.err;
  }
}

TEST(HostileInput, ControlBytesInMessagesAreEscaped) {
  // A file name with a carriage return and an escape sequence: quoted in
  // the message as \x0d and \x1b, so it can neither hide the start of the
  // line nor clear the terminal.
  Folder work, logs;
  const std::string name = (work / "bad\r\x1b[2Jname.nc").string();
  const ChildResult r = run({kVcpost, "moves", name}, logs);
  EXPECT_EQ(r.shell_status(), 2) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("bad\\x0d\\x1b[2Jname.nc"), std::string::npos) << r.err;
}

TEST(HostileInput, EmptyOptionValueIsNamed) {
  // `--ap= -o out.nc` said "--ap: '-o' is not a number" (CLI11 took the
  // next argument as the value) and `--vc= -o out.nc` "--output is
  // required" (it took -o and lost the file name).
  Folder work, logs;
  for (const std::string option : {"--ap", "--vc", "--spacing", "--tool"}) {
    std::vector<std::string> args{kVcpost,
                                  "post",
                                  kDome,
                                  "--model",
                                  (kSamples / "dome.step").string(),
                                  option + "=",
                                  "-o",
                                  (work / "out.nc").string()};
    const ChildResult r = run(args, logs);
    EXPECT_EQ(r.shell_status(), 2) << r.err;
    EXPECT_EQ(r.err, "vcpost: error: " + option + ": empty value after '=' (give " + option +
                         "=VALUE or " + option + " VALUE)\n");
    EXPECT_FALSE(fs::exists(work / "out.nc"));
  }
}

TEST(HostileInput, UnknownCommandIsNamed) {
  Folder logs;
  const ChildResult r = run({kVcpost, "bogus"}, logs);
  EXPECT_EQ(r.shell_status(), 2);
  EXPECT_EQ(r.err,
            "vcpost: error: unknown command 'bogus'; the commands are deff, moves, machines, post, "
            "report, verify, explain (vcpost --help)\n");
}

TEST(HostileInput, StepFileAsMachineIsNamedForWhatItIs) {
  Folder logs;
  const ChildResult r =
      run(dome_job(kDome, {"--machine", (kSamples / "dome.step").string(), "-o", "-"}), logs);
  EXPECT_EQ(r.shell_status(), 2);
  EXPECT_NE(r.err.find("this is a STEP file, not a TOML profile"), std::string::npos) << r.err;
}

TEST(HostileInput, ReaderLeavingEarlyIsNoFailureMessage) {
  // `vcpost post ... -o - | head`: the reader leaves after some bytes; the
  // run ends by SIGPIPE as before, but without "no output written" (bytes
  // were delivered). A program over 64 KB posted (the pipe's buffer).
  Folder work, logs;
  // The dome program with 8,000 comment lines after its '%' (kept byte for
  // byte): about 190 KB posted.
  std::string text = read_file(kDome);
  std::string padding;
  for (int i = 0; i < 8000; ++i) padding += "(padding line " + std::to_string(i) + ")\n";
  text.insert(text.find('\n') + 1, padding);
  write(work / "big.nc", text);
  ASSERT_GT(text.size(), 100000u);
  int fds[2];
  ASSERT_EQ(::pipe2(fds, O_CLOEXEC), 0);  // the child keeps no read end (dup2 clears it on 1)
  std::string got;
  const ChildResult r =
      run(dome_job((work / "big.nc").string(), {"-q", "-o", "-"}), logs, [&](ChildOptions& o) {
        o.stdout_fd = fds[1];
        o.while_running = [&](pid_t) {
          ::close(fds[1]);
          char buffer[4096];
          const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
          if (n > 0) got.assign(buffer, static_cast<std::size_t>(n));
          ::close(fds[0]);  // `head` has seen enough
        };
      });
  EXPECT_FALSE(got.empty());
  EXPECT_FALSE(r.exited);
  EXPECT_EQ(r.signal, SIGPIPE);
  EXPECT_EQ(r.err, "");
}

TEST(HostileInput, StandardOutputCommandsEndQuietlyWhenTheReaderLeaves) {
  // `vcpost moves f.nc | head -1` (and verify --changes, deff --sweep)
  // printed "interrupted by SIGPIPE; no output written": their only output
  // is standard output, so a reader that leaves is their normal end. Each
  // writes well over a pipe's 64 KB here: the dome's transcript (180 KB),
  // 6,000 changed S words, a sweep in 0.01 deg steps.
  Folder work, logs;
  std::string a = "G21 G90 G17 G94\nS1000 M3\n", b = a;
  for (int i = 1; i <= 6000; ++i) {
    const std::string move = "G1 X" + std::to_string(i % 100) + " F100 S";
    a += move + "1000\n";
    b += move + "2000\n";
  }
  a += "M30\n";
  b += "M30\n";
  write(work / "a.nc", a);
  write(work / "b.nc", b);
  const std::vector<std::vector<std::string>> cases = {
      {kVcpost, "moves", kDome},
      {kVcpost, "verify", "--changes", (work / "a.nc").string(), (work / "b.nc").string()},
      {kVcpost, "deff", "--tool", "ball:10", "--ap", "1", "--ae", "1", "--tilt", "25", "--azimuth",
       "35", "--sweep", "feed-angle=0:360:0.01"}};
  for (const auto& args : cases) {
    int fds[2];
    ASSERT_EQ(::pipe2(fds, O_CLOEXEC), 0);
    std::string got;
    const ChildResult r = run(args, logs, [&](ChildOptions& o) {
      o.stdout_fd = fds[1];
      o.while_running = [&](pid_t) {
        ::close(fds[1]);
        char buffer[256];
        const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
        if (n > 0) got.assign(buffer, static_cast<std::size_t>(n));
        ::close(fds[0]);  // `head -1` has seen enough
      };
    });
    EXPECT_FALSE(got.empty()) << joined(args);
    EXPECT_FALSE(r.exited) << joined(args);
    EXPECT_EQ(r.signal, SIGPIPE) << joined(args);
    EXPECT_EQ(r.err, "") << joined(args);
  }
}

}  // namespace
}  // namespace vcpost::test
