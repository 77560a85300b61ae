#include "postproc/cli/held_output.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "postproc/cli/commands.h"

namespace vcpost::cli {
namespace {

std::filesystem::path default_folder() {
  const char* tmpdir = std::getenv("TMPDIR");
  return tmpdir != nullptr && *tmpdir != '\0' ? tmpdir : "/tmp";
}

}  // namespace

HeldOutput::HeldOutput(std::size_t memory_limit, std::filesystem::path folder)
    : limit_(memory_limit), folder_(folder.empty() ? default_folder() : std::move(folder)) {}

HeldOutput::~HeldOutput() {
  if (file_) (void)std::fclose(file_);  // a spill file already read back or abandoned
}

void HeldOutput::fail(const std::string& what, int error) const {
  std::string reason = std::strerror(error);
  if (error == ENOSPC || error == EFBIG || error == EDQUOT) reason += " (free some space there)";
  throw CommandError(Code::E2003, "cannot hold the program for standard output: " + what + " in '" +
                                      folder_.string() + "': " + reason +
                                      " (or write it to a file with -o FILE)");
}

void HeldOutput::append(std::string_view bytes) {
  memory_.append(bytes);
  if (memory_.size() > limit_) spill();
}

void HeldOutput::spill() {
  if (!file_) {
    std::string pattern = (folder_ / "vcpost-stdout.XXXXXX").string();
    const int fd = ::mkstemp(pattern.data());
    if (fd < 0) fail("cannot create a temporary file", errno);
    ::unlink(pattern.c_str());  // only the descriptor keeps it now
    file_ = ::fdopen(fd, "w+b");
    if (!file_) {
      const int error = errno;
      ::close(fd);
      fail("cannot open a temporary file", error);
    }
  }
  if (std::fwrite(memory_.data(), 1, memory_.size(), file_) != memory_.size()) {
    fail("cannot write a temporary file", errno);
  }
  spilled_ += memory_.size();
  memory_.clear();
}

bool HeldOutput::for_each_chunk(const std::function<bool(std::string_view)>& take) {
  if (file_) {
    if (std::fflush(file_) != 0) fail("cannot write a temporary file", errno);
    std::rewind(file_);
    std::string buffer(std::size_t{1} << 20, '\0');
    for (std::uint64_t left = spilled_; left > 0;) {
      const std::size_t want =
          static_cast<std::size_t>(std::min<std::uint64_t>(left, buffer.size()));
      const std::size_t got = std::fread(buffer.data(), 1, want, file_);
      if (got == 0) fail("cannot read back a temporary file", std::ferror(file_) ? errno : EIO);
      if (!take(std::string_view(buffer.data(), got))) return false;
      left -= got;
    }
  }
  return memory_.empty() || take(memory_);
}

bool HeldOutput::write_to(std::ostream& out) {
  return for_each_chunk([&out](std::string_view bytes) {
    return static_cast<bool>(out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())));
  });
}

}  // namespace vcpost::cli
