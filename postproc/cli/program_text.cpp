#include "postproc/cli/program_text.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include "postproc/cli/commands.h"

namespace vcpost::cli {
namespace {

// Pages are released in steps of this many bytes: one madvise call per step.
constexpr std::uint64_t release_step = std::uint64_t{16} << 20;

std::string read_stream(std::istream& in) {
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

ProgramText::ProgramText(const std::string& path) {
  if (path == "-") {
    copy_ = read_stream(std::cin);
    view_ = copy_;
    return;
  }
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    throw CommandError("E2002", "'" + path + "': cannot open the program: " + std::strerror(errno));
  }
  struct stat info {};
  if (::fstat(fd, &info) != 0 || S_ISDIR(info.st_mode)) {
    ::close(fd);
    throw CommandError("E2002", 
        "'" + path + "': cannot open the program: " +
        (S_ISDIR(info.st_mode) ? std::string("it is a folder") : std::strerror(errno)));
  }
  if (!S_ISREG(info.st_mode) || info.st_size == 0) {
    // A pipe, a device, or an empty file: read it (mmap cannot map these).
    ::close(fd);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw CommandError("E2002", "'" + path + "': cannot open the program");
    copy_ = read_stream(in);
    view_ = copy_;
    return;
  }
  map_size_ = static_cast<std::size_t>(info.st_size);
  map_ = ::mmap(nullptr, map_size_, PROT_READ, MAP_PRIVATE, fd, 0);
  const int map_error = errno;
  ::close(fd);
  if (map_ == MAP_FAILED) {
    map_ = nullptr;
    throw CommandError("E2002", "'" + path + "': cannot read the program: " + std::strerror(map_error));
  }
  ::madvise(map_, map_size_, MADV_SEQUENTIAL);
  view_ = std::string_view(static_cast<const char*>(map_), map_size_);
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
