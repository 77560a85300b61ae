// Writing a posted Klartext program: the input with only the speeds, the
// numbering and (with feed coupling) F words changed. A TNC takes no S in
// an L block: the speed of the tool in the spindle changes with a
// `TOOL CALL S<n>` block of its own. So a planned S is
//   - the new value of the S word of the block's own TOOL CALL (the digits
//     replaced in place), where the block is one with an S word;
//   - else a block `<n> TOOL CALL S<rpm>` inserted before the block (the
//     one whose motion starts the new speed), numbered as that block was,
//     and every block after it, END PGM included, numbered one more (only
//     the digits of the number are rewritten);
// a planned F the new digits of the block's F word where it has a plain
// number (F MAX, FMAX, FQn, FAUTO, FU and FZ stay; a block without one gets
// none). Every other byte is copied: comments, blanks, line endings, bytes
// that are not UTF-8. Internal to the post module.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string_view>

#include "postproc/gcode/writer.h"
#include "postproc/heidenhain/block.h"

namespace vcpost::post {

class KlartextPatcher {
 public:
  // REQUIRES: `text` (the whole program) outlives the patcher.
  explicit KlartextPatcher(std::string_view text) : text_(text) {}

  // Whether the block at `offset` has an F word with a plain number (where
  // a coupled F can go).
  bool takes_f(std::uint64_t offset);

  // Writes the text from `from` to `to` (block starts, or the text's end)
  // with `patches` (absolute block offsets, sorted; letter 'S' or 'F') to
  // `sink`. Called with consecutive ranges: the numbering carries on.
  // Throws heidenhain::KlartextError for a block the reader refuses.
  void write(std::uint64_t from, std::uint64_t to, std::span<const gcode::WordPatch> patches,
             const std::function<void(std::string_view)>& sink);

  // TOOL CALL S blocks inserted so far.
  std::uint64_t inserted() const { return inserted_; }

 private:
  void read_block(std::uint64_t offset);
  const heidenhain::Word* plain_f() const;

  std::string_view text_;
  heidenhain::Block block_;
  std::uint64_t inserted_ = 0;  // also what every block number after them grows by
};

}  // namespace vcpost::post
