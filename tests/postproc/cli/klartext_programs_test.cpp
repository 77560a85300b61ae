// The files CALL PGM finds: beside the calling program (relative paths,
// nested calls from the called program's folder), TNC:\ paths from the
// main program's folder, names without case and with .h added.
#include "postproc/cli/klartext_programs.h"

#include <gtest/gtest.h>

#include <fstream>

#include "tests/postproc/temp_folder.h"

namespace vcpost::cli {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

TEST(KlartextProgramFiles, FindsWhatTheControlWouldFind) {
  testing::Folder folder;
  write(folder / "main.h", "BEGIN PGM MAIN MM\nEND PGM MAIN MM\n");
  write(folder / "Sub/Part.H", "part");
  write(folder / "Sub/inner.h", "inner");
  write(folder / "beside.h", "beside");
  const heidenhain::ProgramLoader load = klartext_program_files(folder / "main.h");
  EXPECT_EQ(load("beside.h", "")->text, "beside");
  EXPECT_EQ(load("BESIDE", "")->text, "beside");  // no case, .h added
  EXPECT_EQ(load("Sub\\Part.H", "")->text, "part");
  const auto part = load("TNC:\\Sub\\Part.H", "");
  ASSERT_TRUE(part);
  EXPECT_EQ(part->name, (folder / "Sub/Part.H").string());
  // A call from Sub/Part.H looks in Sub/ first; a TNC:\ path whose folder
  // is not here is looked for beside the caller.
  EXPECT_EQ(load("inner", part->name)->text, "inner");
  EXPECT_EQ(load("TNC:\\nc_prog\\other\\inner.h", part->name)->text, "inner");
  EXPECT_FALSE(load("missing.h", ""));
  EXPECT_FALSE(load("/etc/passwd", ""));  // not a control's path
  EXPECT_FALSE(klartext_program_files("-")("beside.h", ""));
}

}  // namespace
}  // namespace vcpost::cli
