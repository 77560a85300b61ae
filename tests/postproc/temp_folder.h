// A private folder per test under the system's temporary folder, for tests
// that write files: tests run in parallel (ctest -j), so a fixed name races.
#pragma once

#include <stdlib.h>

#include <filesystem>
#include <string>

namespace vcpost::testing {

// A private folder per test, removed at the end (also when read-only).
class Folder {
 public:
  Folder() {
    namespace fs = std::filesystem;
    std::string pattern = (fs::temp_directory_path() / "vcpost-test-XXXXXX").string();
    path_ = ::mkdtemp(pattern.data());
    fs::permissions(path_, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                               fs::perms::others_read | fs::perms::others_exec);
  }
  ~Folder() {
    namespace fs = std::filesystem;
    std::error_code error;
    for (const auto& entry : fs::recursive_directory_iterator(path_, error)) {
      fs::permissions(entry.path(), fs::perms::owner_all, fs::perm_options::add, error);
    }
    fs::remove_all(path_, error);
  }
  Folder(const Folder&) = delete;
  Folder& operator=(const Folder&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace vcpost::testing
