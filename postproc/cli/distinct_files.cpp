#include "postproc/cli/distinct_files.h"

#include <sys/stat.h>

#include <filesystem>
#include <optional>

#include "postproc/cli/atomic_file.h"
#include "postproc/cli/commands.h"

namespace vcpost::cli {
namespace {

// What a name stands for: an existing file's device and inode, or the path
// a new file would be created at.
struct FileKey {
  bool exists = false;
  bool character_device = false;
  // Written in place, not replaced (a device, FIFO or socket, or one of
  // the process's open descriptors such as /dev/stderr): two outputs there
  // follow each other and lose nothing.
  bool in_place = false;
  dev_t device = 0;
  ino_t inode = 0;
  std::filesystem::path created_at;

  bool operator==(const FileKey& o) const {
    if (exists != o.exists) return false;
    return exists ? device == o.device && inode == o.inode : created_at == o.created_at;
  }
};

std::optional<FileKey> key_of(const std::string& path) {
  if (path.empty() || path == "-") return std::nullopt;
  FileKey key;
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0) {
    key.exists = true;
    key.character_device = S_ISCHR(info.st_mode);
    key.in_place = !S_ISREG(info.st_mode) || own_descriptor(path) >= 0;
    key.device = info.st_dev;
    key.inode = info.st_ino;
  } else {
    std::error_code ignored;
    key.created_at = std::filesystem::weakly_canonical(
        std::filesystem::absolute(follow_links(path), ignored), ignored);
  }
  return key;
}

std::string quoted(const NamedFile& f) { return f.role + " '" + f.path + "'"; }

}  // namespace

void require_distinct_files(const std::vector<NamedFile>& inputs,
                            const std::vector<NamedFile>& outputs) {
  std::vector<std::optional<FileKey>> input_keys, output_keys;
  for (const auto& f : inputs) input_keys.push_back(key_of(f.path));
  for (const auto& f : outputs) output_keys.push_back(key_of(f.path));
  for (std::size_t o = 0; o < outputs.size(); ++o) {
    const auto& out = output_keys[o];
    if (!out || out->character_device) continue;
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      if (input_keys[i] && *input_keys[i] == *out) {
        throw CommandError(quoted(outputs[o]) + " is the same file as the input " +
                           quoted(inputs[i]) + "; an input is never overwritten");
      }
    }
    for (std::size_t p = 0; p < o; ++p) {
      if (output_keys[p] && *output_keys[p] == *out &&
          !(out->in_place && output_keys[p]->in_place)) {
        throw CommandError(quoted(outputs[o]) + " is the same file as " + quoted(outputs[p]) +
                           "; give each output its own file");
      }
    }
  }
}

}  // namespace vcpost::cli
