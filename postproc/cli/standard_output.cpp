// finish_standard_output() and printable() (commands.h): what reaches the terminal.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <string_view>

#include "postproc/cli/commands.h"

namespace vcpost::cli {

void write_standard_output(std::string_view bytes) {
  errno = 0;
  if (std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size()) {
    const int error = errno;
    std::clearerr(stdout);
    throw CommandError(std::string("cannot write to standard output: ") +
                       (error != 0 ? std::strerror(error) : "write error"));
  }
}

void finish_standard_output() {
  errno = 0;
  std::cout.flush();
  const bool cxx_failed = !std::cout;
  const bool c_failed = std::fflush(stdout) != 0 || std::ferror(stdout) != 0;
  if (cxx_failed || c_failed) {
    const int error = errno;
    std::cout.clear();
    std::clearerr(stdout);
    throw CommandError(std::string("cannot write to standard output: ") +
                       (error != 0 ? std::strerror(error) : "write error"));
  }
}

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      static constexpr char hex[] = "0123456789abcdef";
      out += "\\x";
      out += hex[byte >> 4];
      out += hex[byte & 15];
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace vcpost::cli
