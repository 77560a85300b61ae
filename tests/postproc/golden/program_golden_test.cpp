// Whole-program golden cases of `vcpost post` (tests/golden/README.md):
// each case folder with a `command` file is a run of the real binary on a
// sample, a program of its own or one the sample generator writes first,
// or a real program of ../shared/data, with its model, and its
// results must equal the stored ones: the exit status, the standard error,
// the written program byte for byte (or its digest when long) and the
// summary JSON (numbers to 1e-9 relative: the last bits of a mean may
// differ with the CPU's libm; the run time is left out).
//
// VCPOST_GOLDEN_UPDATE=1 rewrites the expected files from what vcpost
// writes now (review the diff before committing it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/postproc/faults/child_process.h"
#include "tests/postproc/golden/golden_support.h"

namespace vcpost {
namespace {

namespace fs = std::filesystem;
using golden::read;
using golden::trimmed;

const fs::path kGoldenDir = fs::path(VCPOST_SOURCE_DIR) / "tests/golden";
const std::string kSamples = (fs::path(VCPOST_SOURCE_DIR) / "samples").string();
const std::string kShared = fs::path(VCPOST_SHARED_DATA_DIR).lexically_normal().string();

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at)) {
    text.replace(at, from.size(), to);
    at += to.size();
  }
}

// The folders a case's words name: {samples}, {shared}, {here} (the case's
// own folder) and {out} (the run's fresh one).
struct Folders {
  std::string here;
  std::string out;
};

// The words of a command line with the folders put in.
std::vector<std::string> command_words(const std::string& command, const Folders& folders) {
  std::string text = command;
  replace_all(text, "{samples}", kSamples);
  replace_all(text, "{shared}", kShared);
  replace_all(text, "{here}", folders.here);
  replace_all(text, "{out}", folders.out);
  std::vector<std::string> words;
  std::istringstream in(text);
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

// Paths of this machine written back as the placeholders.
std::string portable(std::string text, const Folders& folders) {
  replace_all(text, folders.out, "{out}");
  replace_all(text, folders.here, "{here}");
  replace_all(text, kShared, "{shared}");
  replace_all(text, kSamples, "{samples}");
  return text;
}

// Runs each line of the case's `generate` file as a command of the sample
// generator (its inputs, written into {out} before the run); the first
// failure's message, or empty.
std::string generate_inputs(const fs::path& file, const Folders& folders) {
  if (!fs::exists(file)) return "";
  std::istringstream lines(read(file));
  for (std::string line; std::getline(lines, line);) {
    if (trimmed(line).empty()) continue;
    std::vector<std::string> argv = command_words(line, folders);
    argv.insert(argv.begin(), VCPOST_SAMPLEGEN);
    test::ChildOptions options;
    options.argv = argv;
    options.stdout_file = fs::path(folders.out) / "generate.out";
    options.stderr_file = fs::path(folders.out) / "generate.err";
    options.timeout_s = 60;
    const test::ChildResult r = test::run_child(options);
    if (r.shell_status() != 0) return "vcpost-samplegen " + line + ": " + r.err;
  }
  return "";
}

// The summary as stored: paths as placeholders, the run time left out.
nlohmann::json stored_summary(const std::string& text, const Folders& folders) {
  nlohmann::json summary = nlohmann::json::parse(portable(text, folders));
  summary.erase("run_time_s");
  return summary;
}

// Equal but for numbers within 1e-9 relative; the first difference's path.
std::string first_difference(const nlohmann::json& want, const nlohmann::json& got,
                             const std::string& where = "") {
  if (want.is_number() && got.is_number()) {
    const double a = want.get<double>(), b = got.get<double>();
    const bool close = a == b || std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b));
    return close ? "" : where + ": " + want.dump() + " != " + got.dump();
  }
  if (want.type() != got.type()) return where + ": " + want.dump() + " != " + got.dump();
  if (want.is_object()) {
    for (const auto& [key, value] : want.items()) {
      if (!got.contains(key)) return where + "/" + key + ": missing";
      const std::string d = first_difference(value, got[key], where + "/" + key);
      if (!d.empty()) return d;
    }
    for (const auto& [key, value] : got.items())
      if (!want.contains(key)) return where + "/" + key + ": not expected";
    return "";
  }
  if (want.is_array()) {
    if (want.size() != got.size()) return where + ": " + std::to_string(got.size()) + " items";
    for (std::size_t i = 0; i < want.size(); ++i) {
      const std::string d = first_difference(want[i], got[i], where + "/" + std::to_string(i));
      if (!d.empty()) return d;
    }
    return "";
  }
  return want == got ? "" : where + ": " + want.dump() + " != " + got.dump();
}

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(GoldenProgram, EveryCaseEqualsItsStoredRun) {
  const bool update = golden::updating();
  int cases = 0, skipped = 0;
  for (const auto& entry : fs::directory_iterator(kGoldenDir)) {
    const fs::path dir = entry.path();
    if (!entry.is_directory() || !fs::exists(dir / "command")) continue;
    const std::string command = trimmed(read(dir / "command"));
    SCOPED_TRACE(dir.filename().string() + ": vcpost " + command);
    if (command.find("{shared}") != std::string::npos && !fs::is_directory(kShared)) {
      ++skipped;
      continue;
    }
    ++cases;
    test::Folder work;
    const Folders folders{dir.string(), work.path().string()};
    const std::string generated = generate_inputs(dir / "generate", folders);
    ASSERT_EQ(generated, "");
    std::vector<std::string> argv = command_words(command, folders);
    argv.insert(argv.begin(), VCPOST_BINARY);
    test::ChildOptions options;
    options.argv = argv;
    options.stdout_file = work / "stdout";
    options.stderr_file = work / "stderr";
    options.timeout_s = 120;
    const test::ChildResult r = test::run_child(options);
    const std::string exit_text = "exit " + std::to_string(r.shell_status()) + "\n";
    const std::string stderr_text = portable(r.err, folders);
    const bool wrote = fs::exists(work / "program");
    const std::string program = wrote ? golden::stored_program(read(work / "program")) : "";
    const bool summarised = fs::exists(work / "summary.json");
    if (update) {
      write(dir / "exit", exit_text);
      write(dir / "stderr", stderr_text);
      if (wrote)
        write(dir / "program", program);
      else
        fs::remove(dir / "program");
      if (summarised)
        write(dir / "summary.json",
              stored_summary(read(work / "summary.json"), folders).dump(2) + "\n");
      else
        fs::remove(dir / "summary.json");
    }
    EXPECT_EQ(read(dir / "exit"), exit_text);
    EXPECT_EQ(read(dir / "stderr"), stderr_text);
    EXPECT_EQ(fs::exists(dir / "program"), wrote);
    EXPECT_EQ(read(dir / "program"), program);
    ASSERT_EQ(fs::exists(dir / "summary.json"), summarised);
    if (summarised) {
      EXPECT_EQ(first_difference(nlohmann::json::parse(read(dir / "summary.json")),
                                 stored_summary(read(work / "summary.json"), folders)),
                "");
    }
  }
  if (skipped > 0)
    std::printf("%d golden program cases skipped: no shared data at %s\n", skipped,
                kShared.c_str());
  EXPECT_GE(cases, 5);
}

}  // namespace
}  // namespace vcpost
