#include "postproc/cli/klartext_programs.h"

#include <deque>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "core/text.h"

namespace vcpost::cli {

namespace {

namespace fs = std::filesystem;

// The file `name` in `folder`, its case as the disk has it; empty if none.
std::optional<fs::path> find_in(const fs::path& folder, const fs::path& name) {
  std::error_code ec;
  const fs::path exact = folder / name;
  if (fs::is_regular_file(exact, ec)) return exact;
  const fs::path dir = exact.parent_path();
  const std::string wanted = to_lower(exact.filename().string());
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (to_lower(it->path().filename().string()) == wanted && it->is_regular_file(ec))
      return it->path();
  }
  return std::nullopt;
}

std::optional<fs::path> find_with_extension(const fs::path& folder, fs::path name) {
  if (auto found = find_in(folder, name)) return found;
  if (!name.has_extension()) return find_in(folder, name.concat(".h"));
  return std::nullopt;
}

class ProgramFiles {
 public:
  explicit ProgramFiles(fs::path main) : main_(std::move(main)) {}

  std::optional<heidenhain::CalledProgram> load(std::string_view written, std::string_view caller) {
    if (main_.empty() || main_ == "-") return std::nullopt;
    std::string path(trim(written));
    for (char& c : path)
      if (c == '\\') c = '/';
    const fs::path caller_folder =
        fs::path(caller.empty() ? main_ : fs::path(caller)).parent_path();
    const fs::path main_folder = main_.parent_path();
    std::optional<fs::path> found;
    if (to_lower(path.substr(0, 4)) == "tnc:") {
      path.erase(0, 4);
      while (!path.empty() && path.front() == '/') path.erase(0, 1);
      found = find_with_extension(main_folder, path);
      if (!found) found = find_with_extension(caller_folder, fs::path(path).filename());
    } else if (!path.empty() && path.front() != '/') {
      found = find_with_extension(caller_folder, path);
    }
    if (!found) return std::nullopt;
    std::ifstream in(*found, std::ios::binary);
    if (!in) return std::nullopt;
    texts_.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return heidenhain::CalledProgram{texts_.back(), found->string()};
  }

 private:
  fs::path main_;
  std::deque<std::string> texts_;  // a deque: the views stay valid as it grows
};

}  // namespace

heidenhain::ProgramLoader klartext_program_files(const std::filesystem::path& main_program) {
  auto files = std::make_shared<ProgramFiles>(main_program);
  return
      [files](std::string_view path, std::string_view caller) { return files->load(path, caller); };
}

}  // namespace vcpost::cli
