#include "postproc/post/klartext_patch.h"

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace vcpost::post {

void KlartextPatcher::read_block(std::uint64_t offset) {
  heidenhain::split_block(text_, offset, 0, block_);
  heidenhain::parse_block(block_);
}

const heidenhain::Word* KlartextPatcher::plain_f() const {
  const heidenhain::Word* f = block_.find(heidenhain::name("F"));
  return f && f->has_value && !f->value.is_parameter() ? f : nullptr;
}

bool KlartextPatcher::takes_f(std::uint64_t offset) {
  read_block(offset);
  return plain_f() != nullptr;
}

void KlartextPatcher::write(std::uint64_t from, std::uint64_t to,
                            std::span<const gcode::WordPatch> patches,
                            const std::function<void(std::string_view)>& sink) {
  struct Edit {
    std::uint64_t begin = 0, end = 0;  // in the text
    std::string digits;
  };
  std::vector<Edit> edits;
  std::size_t k = 0;
  for (std::uint64_t pos = from; pos < to;) {
    read_block(pos);
    const std::uint64_t next = block_.end + block_.eol.size();
    edits.clear();
    std::optional<std::string> new_speed;
    for (; k < patches.size() && patches[k].block_offset == pos; ++k) {
      const gcode::WordPatch& patch = patches[k];
      if (patch.letter == 'S') {
        if (block_.kind == heidenhain::BlockKind::tool_call && block_.s_span) {
          edits.push_back({block_.s_span->begin + 1, block_.s_span->end, patch.value});
        } else {
          new_speed = patch.value;
        }
      } else if (const heidenhain::Word* f = plain_f()) {
        edits.push_back({pos + f->begin + 1, pos + f->end, patch.value});
      }
    }
    if (new_speed) {
      // The new block takes the number the block it precedes had; that one
      // and every later block one more.
      std::string inserted;
      if (block_.number) inserted = std::to_string(*block_.number + inserted_) + " ";
      inserted += "TOOL CALL S" + *new_speed;
      inserted += block_.eol.empty() ? std::string_view("\n") : block_.eol;
      sink(inserted);
      ++inserted_;
    }
    if (block_.number && block_.number_span && inserted_ > 0)
      edits.push_back({block_.number_span->begin, block_.number_span->end,
                       std::to_string(*block_.number + inserted_)});
    std::sort(edits.begin(), edits.end(),
              [](const Edit& a, const Edit& b) { return a.begin < b.begin; });
    std::uint64_t at = pos;
    for (const Edit& edit : edits) {
      sink(text_.substr(at, edit.begin - at));
      sink(edit.digits);
      at = edit.end;
    }
    sink(text_.substr(at, next - at));
    pos = next;
  }
  // Internal invariant, not the user's input: patches name block starts
  // of the range, from the reader's own offsets (logic_error: a bug).
  if (k != patches.size())
    throw std::logic_error("KlartextPatcher: a patch that names no block start");
}

}  // namespace vcpost::post
