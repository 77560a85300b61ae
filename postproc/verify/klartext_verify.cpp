// Klartext in, Klartext out: the blocks compared byte for byte outside the
// digits a post may change (block numbers, TOOL CALL S, plain F) with the
// TOOL CALL S blocks it may insert, then both programs read by the Klartext
// reader and their events compared without speeds and feeds (see verify.h).
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "postproc/heidenhain/block.h"
#include "postproc/heidenhain/diagnostics.h"
#include "postproc/heidenhain/interpreter.h"
#include "postproc/program/transcript.h"
#include "postproc/verify/verify.h"
#include "postproc/verify/verify_detail.h"

namespace vcpost::verify {

namespace {

using heidenhain::Block;
using heidenhain::BlockKind;

// The blocks of a text, one at a time (the reader's syntax layer).
class Blocks {
 public:
  explicit Blocks(std::string_view text) : text_(text) {}
  // The next block, or null at the end.
  const Block* next() {
    if (pos_ >= text_.size()) return nullptr;
    pos_ = heidenhain::split_block(text_, pos_, line_, block_);
    line_ += block_.lines;
    heidenhain::parse_block(block_);
    return &block_;
  }

 private:
  std::string_view text_;
  std::uint64_t pos_ = 0;
  std::uint32_t line_ = 1;
  Block block_;
};

// A block vcpost inserts: `[n] TOOL CALL S<rpm>`, no tool, no other word.
bool is_speed_call(const Block& b) {
  return b.kind == BlockKind::tool_call && b.s_span && b.tool_name.empty() && b.words.size() == 1 &&
         b.comments.empty();
}

bool moves(const Block& b) {
  switch (b.kind) {
    case BlockKind::line:
    case BlockKind::line_normal:
    case BlockKind::line_polar:
    case BlockKind::circle:
    case BlockKind::circle_radius:
    case BlockKind::circle_tangent:
    case BlockKind::circle_polar:
    case BlockKind::cycle_call:
      return true;
    default:
      return false;
  }
}

bool plain_positive(std::string_view digits) {
  if (digits.empty() || digits == ".") return false;
  bool nonzero = false;
  int points = 0;
  for (const char c : digits) {
    if (c == '.') {
      ++points;
    } else if (c < '0' || c > '9') {
      return false;
    } else if (c != '0') {
      nonzero = true;
    }
  }
  return points <= 1 && nonzero;
}

// The pieces of an input block that must stay, between the digits a post
// may change: its number, its TOOL CALL's S, its plain F.
struct Editable {
  std::uint64_t begin = 0, end = 0;  // in the block's text
  char letter = 0;                   // 'N' for the number, 'S', 'F'
};

std::vector<Editable> editable(const Block& b) {
  std::vector<Editable> spans;
  if (b.number_span)
    spans.push_back({b.number_span->begin - b.offset, b.number_span->end - b.offset, 'N'});
  if (b.kind == BlockKind::tool_call && b.s_span)
    spans.push_back({b.s_span->begin + 1 - b.offset, b.s_span->end - b.offset, 'S'});
  const heidenhain::Word* f = b.find(heidenhain::name("F"));
  if (f && f->has_value && !f->value.is_parameter()) spans.push_back({f->begin + 1u, f->end, 'F'});
  std::sort(spans.begin(), spans.end(),
            [](const Editable& x, const Editable& y) { return x.begin < y.begin; });
  return spans;
}

bool is_number_char(char c) { return (c >= '0' && c <= '9') || c == '.'; }

class BlockComparer {
 public:
  BlockComparer(Result& result, ChangeSink& changes, ViolationSink& sink)
      : result_(result), changes_(changes), sink_(sink) {}

  // The line of the output block that did not parse (named E7142); none when all did.
  std::optional<std::uint32_t> unreadable_line() const { return unreadable_line_; }

  void run(std::string_view input, std::string_view output) {
    Blocks in(input), out(output);
    const Block* a = in.next();
    const Block* b = next_output(out);
    std::optional<Block> inserted;  // the last TOOL CALL S inserted, waiting for its move
    while (a || b) {
      if (unreadable_line_) return;
      if (!b) {
        sink_.add(Code::E7139, last_line_ + 1, 1, a->line,
                  "the output ends before the input's block '" + head(*a) + "'");
        return;
      }
      if (!a) {
        sink_.add(Code::E7139, b->line, 1, 0,
                  "the output has a block after the input's last: '" + head(*b) + "'");
        return;
      }
      last_line_ = b->line + b->lines - 1;
      if (!same_block(*a, *b) && is_speed_call(*b)) {
        take_inserted(*a, *b);
        const std::uint32_t line = b->line;
        b = next_output(out);
        if (!moves(*a))
          sink_.add(Code::E7138, line, 1, a->line,
                    "an inserted TOOL CALL S stands before '" + head(*a) +
                        "', a block that does not move the tool");
        continue;
      }
      if (!compare(*a, *b)) return;
      a = in.next();
      b = next_output(out);
    }
  }

  // The output's next block; null at its end or at a block that does not
  // parse, which is named here (E7142): the reader of the events stops
  // there too, and no block after it can be compared.
  const Block* next_output(Blocks& out) {
    try {
      return out.next();
    } catch (const heidenhain::KlartextError& e) {
      const heidenhain::Diagnostic& d = e.diagnostic();
      sink_.add(Code::E7142, d.line, d.column, 0, "the output does not read: " + d.message);
      unreadable_line_ = d.line;
      return nullptr;
    }
  }

 private:
  static std::string head(const Block& b) { return std::string(b.text.substr(0, 60)); }

  // The output block is the input's with only editable digits changed.
  bool same_block(const Block& a, const Block& b) const {
    std::string_view x = a.text, y = b.text;
    std::uint64_t at_x = 0, at_y = 0;
    for (const Editable& e : editable(a)) {
      const std::string_view fixed = x.substr(at_x, e.begin - at_x);
      if (y.substr(at_y, fixed.size()) != fixed) return false;
      at_y += fixed.size();
      while (at_y < y.size() && is_number_char(y[at_y])) ++at_y;
      at_x = e.end;
    }
    return x.substr(at_x) == y.substr(at_y) && a.eol == b.eol;
  }

  void take_inserted(const Block& a, const Block& b) {
    ++inserted_;
    ++result_.inserted_blocks;
    const std::string_view digits =
        b.text.substr(b.s_span->begin + 1 - b.offset, b.s_span->end - b.s_span->begin - 1);
    if (!plain_positive(digits))
      sink_.add(Code::E7140, b.line, 1, a.line,
                "inserted TOOL CALL S" + std::string(digits) +
                    ": the speed is not a plain positive number");
    check_number(a, b, static_cast<std::int64_t>(inserted_) - 1);
    changes_.add(Change{b.line, static_cast<std::uint32_t>(b.s_span->begin - b.offset + 1), a.line,
                        'S', "", "S" + std::string(digits), true});
  }

  void check_number(const Block& a, const Block& b, std::int64_t shift) {
    if (a.number.has_value() != b.number.has_value() ||
        (a.number && static_cast<std::int64_t>(*b.number) != *a.number + shift)) {
      sink_.add(Code::E7137, b.line, 1, a.line,
                "block number " + (b.number ? std::to_string(*b.number) : std::string("none")) +
                    " where " +
                    (a.number ? std::to_string(*a.number + shift) : std::string("none")) +
                    " is due (the input's " +
                    (a.number ? std::to_string(*a.number) : std::string("none")) + " plus " +
                    std::to_string(shift) + " inserted before it)");
    }
  }

  bool compare(const Block& a, const Block& b) {
    if (!same_block(a, b)) {
      sink_.add(Code::E7136, b.line, 1, a.line,
                "block '" + head(b) + "' differs from the input's '" + head(a) +
                    "' beyond its number, S and F digits" +
                    (a.eol != b.eol ? std::string(" (its line ending)") : std::string()));
      return false;
    }
    check_number(a, b, static_cast<std::int64_t>(inserted_));
    // The changed S and F digits, where they differ.
    std::string_view y = b.text;
    std::uint64_t at_x = 0, at_y = 0;
    for (const Editable& e : editable(a)) {
      at_y += e.begin - at_x;
      const std::uint64_t start = at_y;
      while (at_y < y.size() && is_number_char(y[at_y])) ++at_y;
      const std::string_view old_digits = a.text.substr(e.begin, e.end - e.begin);
      const std::string_view new_digits = y.substr(start, at_y - start);
      at_x = e.end;
      if (e.letter == 'N' || old_digits == new_digits) continue;
      const auto column = static_cast<std::uint32_t>(start);  // the letter's, 1-based
      if (!plain_positive(new_digits))
        sink_.add(
            Code::E7140, b.line, column, a.line,
            std::string(1, e.letter) + std::string(new_digits) + ": not a plain positive number");
      changes_.add(Change{b.line, column, a.line, e.letter,
                          std::string(1, e.letter) + std::string(old_digits),
                          std::string(1, e.letter) + std::string(new_digits), false});
    }
    return true;
  }

  Result& result_;
  ChangeSink& changes_;
  ViolationSink& sink_;
  std::uint64_t inserted_ = 0;
  std::uint32_t last_line_ = 0;
  std::optional<std::uint32_t> unreadable_line_;  // of the output block that did not parse
};

bool is_speed_or_feed(const program::Event& e) {
  return std::holds_alternative<program::SetSpindleSpeed>(e) ||
         std::holds_alternative<program::SetFeedRate>(e);
}

// The events of both programs without speeds and feeds, one to one.
// `unreadable_line`: where the block comparison found an output block that
// does not parse, named there already.
void compare_events(std::string_view input, std::string_view output, Result& result,
                    ViolationSink& sink, std::optional<std::uint32_t> unreadable_line) {
  heidenhain::Interpreter in(input), out(output);
  // A called program is the same file for both: read as empty on both
  // sides, the comparison of what the two programs differ in is the same.
  const heidenhain::ProgramLoader same_for_both = [](std::string_view, std::string_view) {
    return std::optional<heidenhain::CalledProgram>(
        heidenhain::CalledProgram{"BEGIN PGM CALLED MM\nEND PGM CALLED MM\n", "called"});
  };
  in.set_program_loader(same_for_both);
  out.set_program_loader(same_for_both);
  std::vector<program::Event> xs, ys;
  std::size_t i = 0, j = 0;
  const auto fill = [](heidenhain::Interpreter& reader, std::vector<program::Event>& events,
                       std::size_t& at) {
    while (at == events.size()) {
      events.clear();
      at = 0;
      if (!reader.next(events)) return false;
      std::erase_if(events, is_speed_or_feed);
    }
    return true;
  };
  for (;;) {
    const bool more_in = fill(in, xs, i);
    bool more_out = false;
    try {
      more_out = fill(out, ys, j);
    } catch (const heidenhain::KlartextError& e) {
      const heidenhain::Diagnostic& d = e.diagnostic();
      if (d.line != unreadable_line)
        sink.add(Code::E7142, d.line, d.column, 0, "the output does not read: " + d.message);
      return;
    }
    if (!more_in && !more_out) return;
    if (!more_in || !more_out) {
      const auto& rest = more_in ? xs[i] : ys[j];
      const auto src = program::source_of(rest);
      sink.add(Code::E7141, more_out ? src.line : 0, 1, more_in ? src.line : 0,
               std::string(more_in ? "the output ends before the input's " : "the output has ") +
                   program::transcript(rest));
      return;
    }
    const program::Event& x = xs[i++];
    const program::Event& y = ys[j++];
    if (program::is_motion(x)) ++result.motions;
    if (!same_event(x, y, false)) {
      sink.add(Code::E7141, program::source_of(y).line, 1, program::source_of(x).line,
               "the output means " + program::transcript(y) + " where the input means " +
                   program::transcript(x));
      return;
    }
  }
}

}  // namespace

Result verify_klartext(std::string_view input, std::string_view output, const Options& options,
                       const std::string& input_name) {
  Result result;
  result.kind = InputKind::klartext;
  ViolationSink sink(options.max_violations);
  ChangeSink changes(result, options.on_change);
  BlockComparer blocks(result, changes, sink);
  try {
    blocks.run(input, output);
    compare_events(input, output, result, sink, blocks.unreadable_line());
  } catch (const heidenhain::KlartextError& e) {
    // The input's: the output's are violations (E7142), caught where it is
    // read. Named with its file as the G-code and CL inputs are.
    const heidenhain::Diagnostic& d = e.diagnostic();
    throw vcpost::Error(d.code, heidenhain::format(d, input_name),
                        {d.file.empty() ? input_name : d.file, d.line, d.column});
  }
  sink.move_into(result);
  return result;
}

}  // namespace vcpost::verify
