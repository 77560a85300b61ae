#include "postproc/cli/atomic_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "postproc/cli/commands.h"

namespace vcpost::cli {
namespace {

std::string reason(int error) {
  std::string text = std::strerror(error);
  if (error == ENOSPC || error == EFBIG || error == EDQUOT) {
    text += " (nothing written: free some space or raise the limit, then run again)";
  }
  return text;
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target) : target_(std::move(target)) {
  std::error_code ignored;
  // Absolute, so the signal handler's unlink does not depend on the working folder.
  const std::filesystem::path absolute = std::filesystem::absolute(target_, ignored);
  const std::filesystem::path folder = absolute.parent_path();
  std::string pattern = (folder / ("." + target_.filename().string() + ".XXXXXX")).string();
  const int fd = registration_.create(pattern);
  if (fd < 0) {
    const int error = errno;
    throw CommandError("E2003", "cannot write '" + target_.string() + "': cannot create a file in '" +
                       (target_.has_parent_path() ? target_.parent_path().string() : ".") +
                       "': " + std::strerror(error));
  }
  temporary_ = pattern;
  // mkstemp makes the file private; give it the mode a new file would get.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  file_ = ::fdopen(fd, "wb");
  if (!file_) {
    const int error = errno;
    ::close(fd);
    fail(error);
  }
}

AtomicFile::~AtomicFile() {
  if (file_) std::fclose(file_);
  // Removed before the registration ends, so no signal finds it unregistered.
  if (!temporary_.empty()) ::unlink(temporary_.c_str());
  registration_.release();
}

void AtomicFile::fail(int error) {
  if (file_) std::fclose(file_);
  file_ = nullptr;
  ::unlink(temporary_.c_str());
  temporary_.clear();
  registration_.release();
  throw CommandError("E2003", "cannot write '" + target_.string() + "': " + reason(error));
}

void AtomicFile::write(std::string_view bytes) {
  if (!file_) throw CommandError("E2003", "cannot write '" + target_.string() + "': already closed");
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) fail(errno);
}

void AtomicFile::commit() {
  if (!file_) throw CommandError("E2003", "cannot write '" + target_.string() + "': already closed");
  int error = 0;
  errno = 0;
  if (std::fflush(file_) != 0 || std::ferror(file_) || ::fsync(::fileno(file_)) != 0) {
    error = errno != 0 ? errno : EIO;
  }
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (error == 0 && !closed) error = errno;
  if (error != 0) fail(error);
  if (::rename(temporary_.c_str(), target_.c_str()) != 0) {
    const int rename_error = errno;
    ::unlink(temporary_.c_str());
    temporary_.clear();
    registration_.release();
    throw CommandError("E2003", "cannot create '" + target_.string() + "': " + std::strerror(rename_error));
  }
  temporary_.clear();
  registration_.committed();
}

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code error;
  return std::filesystem::equivalent(a, b, error) && !error;
}

}  // namespace vcpost::cli
