#include "postproc/cli/program_text.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "postproc/cli/commands.h"
#include "postproc/gcode/block.h"

namespace vcpost::cli {
namespace {

// Pages are scanned and released in steps of this many bytes: small enough
// that the resident size of a long program stays flat (bench/gcode_parse.sh
// allows 4 MB of growth), large enough that madvise is rare (27 calls for
// 55 MB).
constexpr std::uint64_t release_step = std::uint64_t{2} << 20;

std::string temporary_folder() {
  const char* tmpdir = std::getenv("TMPDIR");
  return tmpdir != nullptr && *tmpdir != '\0' ? tmpdir : "/tmp";
}

[[noreturn]] void binary_input(const std::string& name, std::string_view before_nul) {
  const auto line = 1 + std::count(before_nul.begin(), before_nul.end(), '\n');
  const std::size_t last_nl = before_nul.rfind('\n');
  const std::size_t column =
      before_nul.size() - (last_nl == std::string_view::npos ? 0 : last_nl + 1) + 1;
  throw CommandError(Code::E1002,
                     {name, static_cast<std::uint32_t>(line), static_cast<std::uint32_t>(column)},
                     "NUL byte: this is no text program (binary data?); nothing read past it");
}

}  // namespace

ProgramText::ProgramText(const std::string& path) {
  const std::string name = path == "-" ? "<stdin>" : path;
  int fd = STDIN_FILENO;
  if (path != "-") {
    fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
      throw CommandError(Code::E2002,
                         "'" + path + "': cannot open the program: " + std::strerror(errno));
    }
  }
  struct stat info {};
  if (::fstat(fd, &info) != 0 || S_ISDIR(info.st_mode)) {
    const int error = errno;
    if (fd != STDIN_FILENO) ::close(fd);
    throw CommandError(Code::E2002, "'" + name + "': cannot open the program: " +
                                        (S_ISDIR(info.st_mode) ? std::string("it is a folder")
                                                               : std::strerror(error)));
  }
  if (S_ISREG(info.st_mode) && path != "-") {
    const auto size = static_cast<std::size_t>(info.st_size);
    if (size > 0) map(fd, size, name);
    ::close(fd);
    if (map_) refuse_binary(name);
    refuse_cr_only(name);
    return;
  }
  // A pipe, a terminal, a device: copied as it comes into an unlinked file.
  std::string pattern = temporary_folder() + "/vcpost-input.XXXXXX";
  const int copy = ::mkostemp(pattern.data(), O_CLOEXEC);
  if (copy < 0) {
    const int error = errno;
    if (fd != STDIN_FILENO) ::close(fd);
    throw CommandError(Code::E2002, "'" + name + "': cannot hold the program in '" +
                                        temporary_folder() + "': " + std::strerror(error));
  }
  ::unlink(pattern.c_str());
  std::vector<char> buffer(std::size_t{1} << 20);
  std::uint64_t total = 0;
  std::uint64_t newlines = 0;
  std::size_t column = 1;
  for (;;) {
    const ssize_t got = ::read(fd, buffer.data(), buffer.size());
    if (got == 0) break;
    if (got < 0) {
      if (errno == EINTR) continue;
      const int error = errno;
      ::close(copy);
      if (fd != STDIN_FILENO) ::close(fd);
      throw CommandError(Code::E2002,
                         "'" + name + "': cannot read the program: " + std::strerror(error));
    }
    const std::string_view piece(buffer.data(), static_cast<std::size_t>(got));
    if (const std::size_t nul = piece.find('\0'); nul != std::string_view::npos) {
      ::close(copy);
      if (fd != STDIN_FILENO) ::close(fd);
      const std::string_view before = piece.substr(0, nul);
      const auto lines =
          newlines + static_cast<std::uint64_t>(std::count(before.begin(), before.end(), '\n'));
      const std::size_t last_nl = before.rfind('\n');
      const std::size_t col = last_nl == std::string_view::npos ? column + nul : nul - last_nl;
      throw CommandError(
          Code::E1002,
          {name, static_cast<std::uint32_t>(lines + 1), static_cast<std::uint32_t>(col)},
          "NUL byte: this is no text program (binary data?); nothing read past it");
    }
    newlines += static_cast<std::uint64_t>(std::count(piece.begin(), piece.end(), '\n'));
    const std::size_t last_nl = piece.rfind('\n');
    column = last_nl == std::string_view::npos ? column + piece.size() : piece.size() - last_nl;
    for (std::size_t done = 0; done < piece.size();) {
      const ssize_t put = ::write(copy, piece.data() + done, piece.size() - done);
      if (put < 0) {
        if (errno == EINTR) continue;
        const int error = errno;
        ::close(copy);
        if (fd != STDIN_FILENO) ::close(fd);
        throw CommandError(Code::E2002, "'" + name + "': cannot hold the program in '" +
                                            temporary_folder() + "': " + std::strerror(error));
      }
      done += static_cast<std::size_t>(put);
    }
    total += static_cast<std::uint64_t>(got);
    // A line already past the readers' limit is refused at that line: an
    // endless one (`tr '\\0' X < /dev/zero`) is copied no further.
    if (column > gcode::kMaxLineLength + 1) break;
  }
  if (fd != STDIN_FILENO) ::close(fd);
  if (total > 0) map(copy, static_cast<std::size_t>(total), name);
  ::close(copy);
  refuse_cr_only(name);
}

void ProgramText::refuse_cr_only(const std::string& name) const {
  // A first line that ends in a lone CR, with no LF within a line's length:
  // the old Mac line end, which every reader would take as one long line.
  const std::string_view head = view_.substr(0, gcode::kMaxLineLength + 2);
  const std::size_t cr = head.find('\r');
  if (cr == std::string_view::npos || head.find('\n') != std::string_view::npos ||
      cr + 1 >= view_.size())
    return;
  throw CommandError(Code::E2033, {name, 1, static_cast<std::uint32_t>(cr + 1)},
                     "the lines end with a lone CR (old Mac text), which no reader takes as a "
                     "line end: convert them to LF (tr '\\r' '\\n')");
}

void ProgramText::map(int fd, std::size_t size, const std::string& name) {
  map_size_ = size;
  map_ = ::mmap(nullptr, map_size_, PROT_READ, MAP_PRIVATE, fd, 0);
  if (map_ == MAP_FAILED) {
    const int error = errno;
    map_ = nullptr;
    throw CommandError(Code::E2002,
                       "'" + name + "': cannot read the program: " + std::strerror(error));
  }
  ::madvise(map_, map_size_, MADV_SEQUENTIAL);
  view_ = std::string_view(static_cast<const char*>(map_), map_size_);
}

void ProgramText::refuse_binary(const std::string& name) const {
  // Window by window, each dropped after its scan: the resident size stays
  // one window whatever the file's size.
  const auto page = static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
  for (std::uint64_t at = 0; at < map_size_; at += release_step) {
    const std::size_t length =
        static_cast<std::size_t>(std::min<std::uint64_t>(release_step, map_size_ - at));
    if (std::memchr(view_.data() + at, '\0', length) != nullptr) {
      const std::size_t nul = view_.find('\0', at);
      binary_input(name, view_.substr(0, nul));
    }
    const std::uint64_t end = (at + length) / page * page;
    if (end > at) ::madvise(static_cast<char*>(map_) + at, end - at, MADV_DONTNEED);
  }
}

ProgramText::~ProgramText() {
  if (map_) ::munmap(map_, map_size_);
}

void ProgramText::release_before(std::uint64_t offset) {
  if (!map_ || offset < released_ + release_step) return;
  const auto page = static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
  const std::uint64_t end = offset / page * page;
  if (end <= released_) return;
  // Only a hint: a failure leaves the pages where they are.
  ::madvise(static_cast<char*>(map_) + released_, end - released_, MADV_DONTNEED);
  released_ = end;
}

}  // namespace vcpost::cli
