// HeldOutput: the program for standard output, held until the job has
// succeeded, in memory up to a limit and past it in an unlinked temporary
// file (memory stays flat for programs of any length).
#include "postproc/cli/held_output.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "postproc/cli/commands.h"
#include "tests/postproc/faults/child_process.h"

namespace vcpost::cli {
namespace {

namespace fs = std::filesystem;
using test::Folder;
using test::list_folder;

// Lines of a made-up program, different from one another.
std::string line(int i) { return "X" + std::to_string(i) + ".5 Z-" + std::to_string(i % 7) + "\n"; }

TEST(HeldOutput, SmallOutputStaysInMemory) {
  Folder folder;
  HeldOutput held(1000, folder.path());
  std::string expected;
  for (int i = 0; i < 20; ++i) {
    held.append(line(i));
    expected += line(i);
  }
  EXPECT_EQ(held.size(), expected.size());
  EXPECT_EQ(held.memory_bytes(), expected.size());
  EXPECT_EQ(list_folder(folder.path()), std::vector<std::string>{});  // no file made
  std::ostringstream out;
  EXPECT_TRUE(held.write_to(out));
  EXPECT_EQ(out.str(), expected);
}

TEST(HeldOutput, LongOutputSpillsToAnUnlinkedFileAndComesBackInOrder) {
  Folder folder;
  std::string expected;
  {
    HeldOutput held(100, folder.path());
    for (int i = 0; i < 20000; ++i) {  // about 250 kB: 2500 times the limit
      held.append(line(i));
      expected += line(i);
      ASSERT_LE(held.memory_bytes(), 100u + line(i).size()) << i;
    }
    EXPECT_EQ(held.size(), expected.size());
    // The temporary file was unlinked when made: nothing in the folder.
    EXPECT_EQ(list_folder(folder.path()), std::vector<std::string>{});
    std::ostringstream out;
    EXPECT_TRUE(held.write_to(out));
    EXPECT_EQ(out.str(), expected);
  }
  EXPECT_EQ(list_folder(folder.path()), std::vector<std::string>{});
}

TEST(HeldOutput, AFolderThatCannotTakeTheFileIsAnErrorNamingIt) {
  Folder folder;
  const fs::path missing = folder.path() / "gone";
  HeldOutput held(10, missing);
  try {
    held.append("G1 X1 Y2 Z3 S1000\n");
    ADD_FAILURE() << "spilled into a missing folder";
  } catch (const CommandError& e) {
    EXPECT_EQ(e.exit_code(), exit_input_error);
    EXPECT_EQ(std::string(e.what()),
              "cannot hold the program for standard output: cannot create a temporary file in '" +
                  missing.string() +
                  "': No such file or directory (or write it to a file with -o FILE)");
  }
}

TEST(HeldOutput, AStreamThatFailsIsReported) {
  HeldOutput held(10);
  held.append("G1 X1 Y2 Z3 S1000\nG1 X2\n");
  std::ostringstream out;
  out.setstate(std::ios::badbit);
  EXPECT_FALSE(held.write_to(out));
}

}  // namespace
}  // namespace vcpost::cli
