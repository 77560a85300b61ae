// One small bad CL file per diagnostic in tests/postproc/bad/cldata, each
// with its expected message on its first line ("$$ expect: line:col:
// error[E31xx]: ..."), as LinuxCNC's tests/interp/bad do. Each must give
// exactly that diagnostic (an error, or a warning while reading goes on),
// and nothing may throw anything but ClError.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "postproc/cldata/cl_reader.h"
#include "tests/postproc/codes_in_sources_support.h"

namespace vcpost::cldata {
namespace {

namespace fs = std::filesystem;

TEST(ClBadFiles, EachGivesItsExpectedDiagnostic) {
  const fs::path dir = fs::path(VCPOST_SOURCE_DIR) / "tests/postproc/bad/cldata";
  ASSERT_TRUE(fs::is_directory(dir));
  std::set<std::string> codes_seen;
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".cl") continue;
    ++files;
    SCOPED_TRACE(entry.path().filename().string());
    std::ifstream in(entry.path(), std::ios::binary);
    std::string first;
    std::getline(in, first);
    const std::string prefix = "$$ expect: ";
    ASSERT_EQ(first.rfind(prefix, 0), 0u) << "first line must be the expected message";
    const std::string expected = first.substr(prefix.size());
    in.clear();
    in.seekg(0);
    ClReader reader(in, "");
    std::vector<std::string> got;
    try {
      while (reader.next()) {
      }
    } catch (const ClError& e) {
      got.push_back(e.what());
      codes_seen.insert(std::string(e.id()));
    }
    for (const auto& w : reader.warnings()) {
      got.push_back(format(w, ""));
      codes_seen.insert(std::string(to_string(w.code)));
    }
    EXPECT_NE(std::find(got.begin(), got.end(), expected), got.end())
        << "expected: " << expected << "\n got: " << (got.empty() ? "(nothing)" : got.front());
  }
  EXPECT_GE(files, 30);
  // Every code the reader raises has a bad file, but the line-length limit
  // (tested with a generated 10 MB line in cl_record_reader_test) and the
  // warnings of tools and options it passes (W3153, W3154).
  std::set<std::string> raised = testing::codes_in_sources("postproc/cldata");
  EXPECT_GT(raised.size(), 20u);
  for (const char* tested_elsewhere : {"E3101", "W3153", "W3154"}) raised.erase(tested_elsewhere);
  for (const std::string& code : raised)
    EXPECT_TRUE(codes_seen.contains(code)) << "no bad file for " << code;
}

}  // namespace
}  // namespace vcpost::cldata
