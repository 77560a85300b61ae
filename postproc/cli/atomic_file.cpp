#include "postproc/cli/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "postproc/cli/commands.h"
#include "postproc/cli/held_output.h"

namespace vcpost::cli {
namespace {

std::string reason(int error) {
  std::string text = std::strerror(error);
  if (error == ENOSPC || error == EFBIG || error == EDQUOT) {
    text += " (nothing written: free some space or raise the limit, then run again)";
  }
  return text;
}

// Writes all of `bytes` to `fd`, retrying short writes; false with errno set.
bool write_all(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

// Whether `folder` (canonical) is this process's (or one of its threads')
// folder of open descriptors: /proc/<pid>/fd or /proc/<pid>/task/<tid>/fd.
bool own_descriptor_folder(const std::filesystem::path& folder) {
  if (folder.filename() != "fd") return false;
  const std::filesystem::path own = "/proc/" + std::to_string(::getpid());
  const std::filesystem::path up = folder.parent_path();
  return up == own ||
         (up.parent_path().filename() == "task" && up.parent_path().parent_path() == own);
}

}  // namespace

int own_descriptor(const std::filesystem::path& path) {
  std::filesystem::path p = path;
  for (int hops = 0; hops < 40; ++hops) {
    const std::string name = p.filename().string();
    if (!name.empty() && name.size() < 10 &&
        name.find_first_not_of("0123456789") == std::string::npos) {
      std::error_code error;
      const std::filesystem::path folder =
          std::filesystem::canonical(p.has_parent_path() ? p.parent_path() : ".", error);
      if (!error && own_descriptor_folder(folder)) return std::stoi(name);
    }
    struct stat info {};
    if (::lstat(p.c_str(), &info) != 0 || !S_ISLNK(info.st_mode)) return -1;
    std::error_code error;
    const std::filesystem::path next = std::filesystem::read_symlink(p, error);
    if (error) return -1;
    p = next.is_absolute() ? next : p.parent_path() / next;
  }
  return -1;
}

std::filesystem::path follow_links(const std::filesystem::path& path) {
  std::filesystem::path p = path;
  for (int hops = 0; hops < 40; ++hops) {
    struct stat info {};
    if (::lstat(p.c_str(), &info) != 0 || !S_ISLNK(info.st_mode)) return p;
    std::error_code error;
    const std::filesystem::path next = std::filesystem::read_symlink(p, error);
    if (error) return p;
    p = next.is_absolute() ? next : p.parent_path() / next;
  }
  throw CommandError(Code::E2003, "cannot write '" + path.string() + "': " + std::strerror(ELOOP));
}

AtomicFile::AtomicFile(std::filesystem::path target)
    : target_(std::move(target)), written_(follow_links(target_)) {
  descriptor_ = own_descriptor(target_);
  if (descriptor_ >= 0) {
    // One of our own open files (standard output or error): written into
    // the descriptor as it is, whatever is behind it.
    const int flags = ::fcntl(descriptor_, F_GETFL);
    const std::string why = flags < 0                         ? std::strerror(errno)
                            : (flags & O_ACCMODE) == O_RDONLY ? "it is open for reading only"
                                                              : "";
    if (!why.empty())
      throw CommandError(Code::E2003, "cannot write '" + target_.string() + "': " + why);
    written_ = target_;
    held_ = std::make_unique<HeldOutput>();
    return;
  }
  struct stat info {};
  const bool exists = ::stat(written_.c_str(), &info) == 0;
  if (exists && S_ISDIR(info.st_mode)) {
    throw CommandError(Code::E2003, "cannot write '" + target_.string() + "': it is a folder");
  }
  if (exists && !S_ISREG(info.st_mode)) {
    // A device, FIFO or terminal: written in place on commit. Opening a FIFO
    // now would block, or tell its reader the output ended: check only.
    if (::access(written_.c_str(), W_OK) != 0) {
      throw CommandError(Code::E2003,
                         "cannot write '" + target_.string() + "': " + std::strerror(errno));
    }
    held_ = std::make_unique<HeldOutput>();
    return;
  }
  if (exists && info.st_nlink > 1) {
    throw CommandError(Code::E2003,
                       "cannot write '" + target_.string() + "': it has " +
                           std::to_string(info.st_nlink) +
                           " hard links and replacing it would split it from the others; remove "
                           "it first or write elsewhere");
  }
  std::error_code ignored;
  // Absolute, so the signal handler's unlink does not depend on the working folder.
  const std::filesystem::path absolute = std::filesystem::absolute(written_, ignored);
  const std::filesystem::path folder = absolute.parent_path();
  std::string pattern = (folder / ("." + written_.filename().string() + ".XXXXXX")).string();
  const int fd = registration_.create(pattern);
  if (fd < 0) {
    const int error = errno;
    throw CommandError(Code::E2003,
                       "cannot write '" + target_.string() + "': cannot create a file in '" +
                           (written_.has_parent_path() ? written_.parent_path().string() : ".") +
                           "': " + std::strerror(error));
  }
  temporary_ = pattern;
  if (exists) {
    // The output keeps the mode (and, when allowed, the owner) it had.
    ::fchmod(fd, info.st_mode & 07777);
    if (::fchown(fd, info.st_uid, info.st_gid) != 0) {
      // Not permitted for another user's file: it becomes ours, as with any new file.
    }
  } else {
    // mkstemp makes the file private; give it the mode a new file would get.
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(fd, 0666 & ~mask);
  }
  file_ = ::fdopen(fd, "wb");
  if (!file_) {
    const int error = errno;
    ::close(fd);
    fail(error);
  }
}

AtomicFile::~AtomicFile() {
  // The temporary is discarded: an error closing it changes nothing.
  if (file_) (void)std::fclose(file_);
  // Removed before the registration ends, so no signal finds it unregistered.
  if (!temporary_.empty()) ::unlink(temporary_.c_str());
  registration_.release();
}

void AtomicFile::fail(int error) {
  if (file_) (void)std::fclose(file_);  // discarded, the first error is reported
  file_ = nullptr;
  if (!temporary_.empty()) ::unlink(temporary_.c_str());
  temporary_.clear();
  registration_.release();
  throw CommandError(Code::E2003, "cannot write '" + target_.string() + "': " + reason(error));
}

void AtomicFile::write(std::string_view bytes) {
  if (held_) {
    held_->append(bytes);
    return;
  }
  if (!file_)
    throw CommandError(Code::E2003, "cannot write '" + target_.string() + "': already closed");
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) fail(errno);
}

void AtomicFile::commit_in_place() {
  const int fd = descriptor_ >= 0 ? descriptor_ : ::open(written_.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) fail(errno);
  int error = 0;
  held_->for_each_chunk([&](std::string_view bytes) {
    if (write_all(fd, bytes)) return true;
    error = errno;
    return false;
  });
  if (descriptor_ < 0 && ::close(fd) != 0 && error == 0 && errno != EINTR) error = errno;
  held_.reset();
  if (error != 0) fail(error);
}

void AtomicFile::commit() {
  if (held_) return commit_in_place();
  if (!file_)
    throw CommandError(Code::E2003, "cannot write '" + target_.string() + "': already closed");
  int error = 0;
  errno = 0;
  if (std::fflush(file_) != 0 || std::ferror(file_) || ::fsync(::fileno(file_)) != 0) {
    error = errno != 0 ? errno : EIO;
  }
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (error == 0 && !closed) error = errno;
  if (error != 0) fail(error);
  if (::rename(temporary_.c_str(), written_.c_str()) != 0) {
    const int rename_error = errno;
    ::unlink(temporary_.c_str());
    temporary_.clear();
    registration_.release();
    throw CommandError(Code::E2003,
                       "cannot create '" + target_.string() + "': " + std::strerror(rename_error));
  }
  temporary_.clear();
  registration_.committed();
}

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code error;
  return std::filesystem::equivalent(a, b, error) && !error;
}

}  // namespace vcpost::cli
