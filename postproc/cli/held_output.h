// Standard output that appears only once the job has succeeded (a pipe
// never gets half a program), without holding a long program in memory:
// past `memory_limit` bytes the text goes on into a temporary file that is
// unlinked as soon as it is made, so nothing is left behind whatever ends
// the process (an error, a signal, a crash).
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>

namespace vcpost::cli {

class HeldOutput {
 public:
  // folder: where the temporary file goes, by default $TMPDIR or /tmp.
  explicit HeldOutput(std::size_t memory_limit = std::size_t{64} << 20,
                      std::filesystem::path folder = {});
  HeldOutput(const HeldOutput&) = delete;
  HeldOutput& operator=(const HeldOutput&) = delete;
  ~HeldOutput();

  // Throws CommandError (exit 2) naming the folder and the system's reason
  // when the temporary file cannot be made or written (e.g. disk full).
  void append(std::string_view bytes);
  // Everything appended, in order; returns whether `out` took it all.
  bool write_to(std::ostream& out);
  // Everything appended, in order, in chunks given to `take` until it
  // returns false; returns whether it took them all.
  bool for_each_chunk(const std::function<bool(std::string_view)>& take);

  std::uint64_t size() const { return spilled_ + memory_.size(); }
  std::size_t memory_bytes() const { return memory_.size(); }  // held in memory now

 private:
  void spill();
  [[noreturn]] void fail(const std::string& what, int error) const;

  std::size_t limit_;
  std::filesystem::path folder_;
  std::string memory_;
  std::FILE* file_ = nullptr;  // the unlinked temporary file, once needed
  std::uint64_t spilled_ = 0;  // bytes in it
};

}  // namespace vcpost::cli
