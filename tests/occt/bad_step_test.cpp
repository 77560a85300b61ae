// Bad STEP files (tests/occt/bad, listed with their expected code and
// message in expected.txt): each is refused by BrepModel::load_step with its
// code, and by `vcpost post --model FILE` with exit 2, the path and the code
// on stderr, nothing on stdout and no output file. Among them files that
// OpenCASCADE itself reads without refusing: an entity it cannot parse (it
// would load the rest), a coordinate of 1.E400, a mass as the length unit.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "geometry/occt/brep_model.h"
#include "tests/postproc/faults/child_process.h"

namespace vcpost::occt {
namespace {

namespace fs = std::filesystem;

const fs::path kBad = fs::path(VCPOST_SOURCE_DIR) / "tests/occt/bad";

struct Entry {
  std::string file, code, fragment;
};

std::vector<Entry> entries() {
  std::ifstream list(kBad / "expected.txt");
  std::vector<Entry> out;
  std::string line;
  while (std::getline(list, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto a = line.find('\t'), b = line.find('\t', a + 1);
    if (a == std::string::npos || b == std::string::npos) {
      ADD_FAILURE() << "malformed line in expected.txt: " << line;
      continue;
    }
    out.push_back({line.substr(0, a), line.substr(a + 1, b - a - 1), line.substr(b + 1)});
  }
  return out;
}

TEST(BadStep, ExpectedListCoversEveryFile) {
  const auto list = entries();
  std::vector<std::string> listed, present;
  for (const auto& e : list) listed.push_back(e.file);
  for (const auto& entry : fs::directory_iterator(kBad)) {
    if (entry.path().filename() != "expected.txt")
      present.push_back(entry.path().filename().string());
  }
  std::sort(listed.begin(), listed.end());
  std::sort(present.begin(), present.end());
  EXPECT_EQ(listed, present);
  EXPECT_GE(list.size(), 17u);
}

TEST(BadStep, LoadStepThrowsTheExpectedCode) {
  for (const Entry& e : entries()) {
    SCOPED_TRACE(e.file);
    const fs::path path = kBad / e.file;
    try {
      BrepModel::load_step(path);
      ADD_FAILURE() << "loaded without error";
    } catch (const ModelError& error) {
      const std::string what = error.what();
      EXPECT_EQ(error.id(), e.code);
      EXPECT_EQ(what.rfind(path.string() + ": error[" + e.code + "]: ", 0), 0u) << what;
      EXPECT_NE(what.find(e.fragment), std::string::npos) << what;
    }
  }
  // A file never written by anyone.
  try {
    BrepModel::load_step(kBad / "no_such_file.step");
    ADD_FAILURE() << "a missing file loaded";
  } catch (const ModelError& error) {
    EXPECT_EQ(error.code(), Code::E4101);
  }
}

TEST(BadStep, VcpostPostRefusesEachWithExit2AndNoOutput) {
  namespace t = vcpost::test;
  const fs::path work =
      fs::temp_directory_path() / ("vcpost-bad-step-" + std::to_string(::getpid()));
  fs::create_directories(work);
  // A pass over the square's middle, tip on its plane: it would touch a
  // good square.
  const fs::path program = work / "square.nc";
  std::ofstream(program) << "G21 G90\nG0 X0 Y5 Z5\nS3000 M3\nG1 Z0 F500\nG1 X10\nM2\n";
  for (const Entry& e : entries()) {
    SCOPED_TRACE(e.file);
    const fs::path model = kBad / e.file;
    const auto before = fs::is_regular_file(model) ? t::file_hash(model) : 0;
    t::ChildOptions o;
    o.argv = {VCPOST_BINARY,
              "post",
              program.string(),
              "--model",
              model.string(),
              "--tool",
              "ball:6",
              "--vc",
              "100",
              "--ap",
              "0.2",
              "--ae",
              "0.5",
              "-q",
              "-o",
              (work / "out.nc").string()};
    o.stdout_file = work / "stdout.txt";
    o.stderr_file = work / "stderr.txt";
    const t::ChildResult r = t::run_child(o);
    EXPECT_EQ(r.shell_status(), 2) << r.err;
    // Nothing on stdout (OCCT's reader prints there unless silenced), where
    // `-o -` would put the program.
    EXPECT_EQ(r.out, "");
    const std::string head = "vcpost: error: " + model.string() + ": error[" + e.code + "]: ";
    EXPECT_EQ(r.err.rfind(head, 0), 0u) << r.err;
    EXPECT_NE(r.err.find(e.fragment), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(work / "out.nc"));
    if (fs::is_regular_file(model)) {
      EXPECT_EQ(t::file_hash(model), before);
    }
  }
  EXPECT_EQ(t::list_folder(work),
            (std::vector<std::string>{"square.nc", "stderr.txt", "stdout.txt"}));
  fs::remove_all(work);
}

}  // namespace
}  // namespace vcpost::occt
