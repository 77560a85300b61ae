// G-code in, G-code out: the lexical proof (lines and tokens) and the
// semantic proof (interpreted events), see verify.h.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "postproc/gcode/block.h"
#include "postproc/gcode/diagnostics.h"
#include "postproc/gcode/interpreter.h"
#include "postproc/verify/lexer.h"
#include "postproc/verify/verify.h"
#include "postproc/verify/verify_detail.h"

namespace vcpost::verify {

namespace {

std::string quoted(std::string_view text) { return "'" + std::string(text) + "'"; }

std::string eol_name(std::string_view eol) {
  if (eol == "\r\n") return "CRLF";
  if (eol == "\n") return "LF";
  return "none (end of file)";
}

int letter_index(char letter) { return letter == 'S' ? 0 : 1; }

// A plain number's value ("67", "0"); none for anything else.
std::optional<double> number_of(std::string_view text) {
  double v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return v;
}

// An analog-output word M67/M68 E<n> Q<value> in a line's tokens (blanks
// between its words): the indices of its M and its Q token.
struct AnalogTokens {
  std::size_t m = 0, q = 0;
};
// The first one of output `output` (any output when none is given).
std::optional<AnalogTokens> find_analog(const std::vector<Token>& tokens,
                                        std::optional<int> output) {
  const auto next_word = [&](std::size_t k) {
    ++k;
    while (k < tokens.size() && tokens[k].kind == TokenKind::blank) ++k;
    return k;
  };
  for (std::size_t k = 0; k < tokens.size(); ++k) {
    if (tokens[k].letter() != 'M') continue;
    const auto code = number_of(tokens[k].value());
    if (!code || (*code != 67 && *code != 68)) continue;
    const std::size_t e = next_word(k);
    if (e >= tokens.size() || tokens[e].letter() != 'E') continue;
    const auto n = number_of(tokens[e].value());
    if (!n || (output && *n != *output)) continue;
    const std::size_t q = next_word(e);
    if (q < tokens.size() && tokens[q].letter() == 'Q') return AnalogTokens{k, q};
  }
  return std::nullopt;
}

// S and F words that set no speed or feed on the control, so that a
// change of theirs is a change of the program: G65's macro arguments
// (S and F), Sinumerik's G25/G26 spindle limits (S) and its G4 dwell's
// time (F seconds, S spindle turns; `siemens`). Decided by the input's
// line and applied to both.
void mark_arguments(const std::vector<Token>& decide, bool siemens, std::vector<Token>& tokens) {
  bool macro = false, limit = false, dwell = false;
  for (const Token& t : decide) {
    if (t.letter() != 'G') continue;
    const auto code = number_of(t.value());
    macro = macro || code == 65.0;
    limit = limit || code == 25.0 || code == 26.0;
    dwell = dwell || (siemens && code == 4.0);
  }
  if (!macro && !limit && !dwell) return;
  for (Token& t : tokens)
    if (t.letter() == 'S' || ((macro || dwell) && t.letter() == 'F')) t.kind = TokenKind::argument;
}

// Compares one line of the input with the same line of the output.
class LineComparer {
 public:
  LineComparer(std::optional<int> speed_output, bool siemens)
      : speed_output_(speed_output), siemens_(siemens) {}

  // Appends the line's changes (by column) and violations to `changes` / `sink`.
  void compare(const Line& in, const Line& out, std::vector<Change>& changes, ViolationSink& sink) {
    const std::size_t first = changes.size();
    compare_tokens(in, out, changes, sink);
    std::stable_sort(changes.begin() + static_cast<std::ptrdiff_t>(first), changes.end(),
                     [](const Change& a, const Change& b) { return a.column < b.column; });
  }

 private:
  void compare_tokens(const Line& in, const Line& out, std::vector<Change>& changes,
                      ViolationSink& sink) {
    tokenize(in.text, a_);
    tokenize(out.text, b_);
    mark_arguments(a_, siemens_, b_);
    mark_arguments(a_, siemens_, a_);
    if (!fold_speed_output(in, out, changes, sink)) return;
    if (in.eol != out.eol)
      sink.add(Code::E7102, out.number, static_cast<std::uint32_t>(out.text.size() + 1), in.number,
               "line ends with " + eol_name(out.eol) + " where the input has " + eol_name(in.eol));

    std::array<int, 2> count_a{0, 0}, count_b{0, 0};
    for (const auto& t : a_)
      if (t.is_sf()) ++count_a[letter_index(t.letter())];
    for (const auto& t : b_)
      if (t.is_sf()) ++count_b[letter_index(t.letter())];

    // Words of a letter the input's line lacks are added (as the writer adds
    // them, with the one blank it puts in front); a second one is repeated.
    kept_.clear();
    std::array<bool, 2> seen{false, false};
    for (std::size_t k = 0; k < b_.size(); ++k) {
      const Token& t = b_[k];
      if (!t.is_sf() || count_a[letter_index(t.letter())] > 0) {
        kept_.push_back(t);
        continue;
      }
      if (!kept_.empty() && kept_.back().kind == TokenKind::blank && kept_.back().text == " ")
        kept_.pop_back();
      bool& first = seen[letter_index(t.letter())];
      if (first) {
        sink.add(
            Code::E7110, out.number, t.column, in.number,
            quoted(t.text) + " is a second " + std::string(1, t.letter()) + " word in this block");
        continue;
      }
      first = true;
      if (!is_plain_positive(t.value()))
        sink.add(Code::E7111, out.number, t.column, in.number,
                 "added " + quoted(t.text) + ": the value is not a plain positive number");
      changes.push_back(
          Change{out.number, t.column, in.number, t.letter(), "", std::string(t.text), true});
    }

    std::size_t i = 0, j = 0;
    while (i < a_.size() && j < kept_.size()) {
      const Token& x = a_[i];
      const Token& y = kept_[j];
      const bool same_sf_word = x.is_sf() && y.kind == TokenKind::word && y.text[0] == x.text[0];
      if (same_sf_word && x.text != y.text) {
        if (!is_plain_positive(y.value()))
          sink.add(Code::E7111, out.number, y.column, in.number,
                   quoted(x.text) + " became " + quoted(y.text) +
                       ": the value is not a plain positive number");
        changes.push_back(Change{out.number, y.column, in.number, x.letter(), std::string(x.text),
                                 std::string(y.text), false});
      } else if (x.text != y.text || x.kind != y.kind) {
        report(in, out, i, j, count_a, count_b, sink);
        return;
      }
      ++i;
      ++j;
    }
    if (i < a_.size() || j < kept_.size()) report(in, out, i, j, count_a, count_b, sink);
  }

  // The output's analog speed word (Options::speed_output) as the writer
  // puts it: a change of the input's own one (its Q), the input's S word
  // in another form, or a word added after the block's last one. Folded
  // back into what the input holds there, so that the comparison that
  // follows checks every other byte. False: the line is judged already.
  bool fold_speed_output(const Line& in, const Line& out, std::vector<Change>& changes,
                         ViolationSink& sink) {
    if (!speed_output_) {
      const auto added = find_analog(b_, std::nullopt);
      if (!added || find_analog(a_, std::nullopt)) return true;
      sink.add(Code::E7151, out.number, b_[added->m].column, in.number,
               quoted(b_[added->m].text) +
                   " sets an analog output the input does not: if it carries the spindle "
                   "speed, give verify the --machine whose output.speed_word names it");
      return false;
    }
    const auto word = find_analog(b_, speed_output_);
    if (!word) return true;
    const Token& m = b_[word->m];
    Token& q = b_[word->q];
    const std::size_t begin = m.column - 1;
    const std::string text(out.text.substr(begin, q.column - 1 + q.text.size() - begin));
    if (!is_plain_positive(q.value()))
      sink.add(Code::E7150, out.number, q.column, in.number,
               quoted(text) + ": the speed is not a plain positive number");
    if (const auto own = find_analog(a_, speed_output_)) {
      const Token& q_in = a_[own->q];
      if (q_in.text != q.text) {
        const std::size_t at = a_[own->m].column - 1;
        changes.push_back(Change{
            out.number, m.column, in.number, 'S',
            std::string(in.text.substr(at, q_in.column - 1 + q_in.text.size() - at)), text, false});
        q.text = q_in.text;
      }
      return true;
    }
    const auto s_word = [](const Token& t) { return t.letter() == 'S'; };
    const auto s_in = std::find_if(a_.begin(), a_.end(), s_word);
    const auto m_at = b_.begin() + static_cast<std::ptrdiff_t>(word->m);
    const auto q_end = b_.begin() + static_cast<std::ptrdiff_t>(word->q) + 1;
    if (s_in != a_.end() && std::none_of(b_.begin(), b_.end(), s_word)) {
      // In the S word's place: compared as that S word from here on.
      changes.push_back(
          Change{out.number, m.column, in.number, 'S', std::string(s_in->text), text, false});
      Token s = *s_in;
      s.column = m.column;
      b_.erase(m_at + 1, q_end);
      b_[word->m] = s;
      return true;
    }
    // Added after the block's last word, with the one blank the writer puts in front.
    changes.push_back(Change{out.number, m.column, in.number, 'S', "", text, true});
    auto from = m_at;
    if (from != b_.begin() && std::prev(from)->kind == TokenKind::blank &&
        std::prev(from)->text == " ")
      --from;
    b_.erase(from, q_end);
    return true;
  }

  // The first difference at a_[i] / kept_[j] (either may be past the end).
  void report(const Line& in, const Line& out, std::size_t i, std::size_t j,
              const std::array<int, 2>& count_a, const std::array<int, 2>& count_b,
              ViolationSink& sink) {
    const Token* x = i < a_.size() ? &a_[i] : nullptr;
    const Token* y = j < kept_.size() ? &kept_[j] : nullptr;
    const std::uint32_t column = y ? y->column : static_cast<std::uint32_t>(out.text.size() + 1);
    auto add = [&](Code code, std::string message) {
      sink.add(code, out.number, column, in.number, std::move(message));
    };
    // The input's column, when an added word has shifted it.
    const std::string in_col =
        x && x->column != column ? " (input column " + std::to_string(x->column) + ")" : "";
    if (x && x->is_sf() && !(y && y->kind == TokenKind::word && y->text[0] == x->text[0]) &&
        count_b[letter_index(x->letter())] < count_a[letter_index(x->letter())]) {
      add(Code::E7109, quoted(x->text) + " removed" + in_col);
      return;
    }
    if (y && y->is_sf() &&
        count_b[letter_index(y->letter())] > count_a[letter_index(y->letter())]) {
      add(Code::E7110,
          quoted(y->text) + " is a second " + std::string(1, y->letter()) + " word in this block");
      return;
    }
    if ((x && x->kind == TokenKind::blank) || (y && y->kind == TokenKind::blank)) {
      if (x && y && x->kind == TokenKind::blank && y->kind == TokenKind::blank)
        add(Code::E7106, "blanks " + quoted(x->text) + " became " + quoted(y->text) + in_col);
      else if (x && x->kind == TokenKind::blank)
        add(Code::E7106, "blank " + quoted(x->text) + " removed" + in_col);
      else
        add(Code::E7106, "blank " + quoted(y->text) + " added");
      return;
    }
    if (x && y && x->kind == TokenKind::comment && y->kind == TokenKind::comment) {
      if (comment_words_only(x->text, y->text))
        add(Code::E7108, "an S/F word inside the comment changed: " + quoted(x->text) + " became " +
                             quoted(y->text) + " (comments are never edited)");
      else
        add(Code::E7107, "comment " + quoted(x->text) + " became " + quoted(y->text));
      return;
    }
    // One token missing or extra, when the rest lines up again after it.
    auto same = [](const std::vector<Token>& v, std::size_t k, const Token* t) {
      return t && k < v.size() && v[k].text == t->text;
    };
    const bool removed =
        x && (same(a_, i + 1, y) ||
              (i + 1 < a_.size() && a_[i + 1].kind == TokenKind::blank && same(a_, i + 2, y)) ||
              (!y && i + 1 == a_.size()));
    const bool added =
        y &&
        (same(kept_, j + 1, x) ||
         (j + 1 < kept_.size() && kept_[j + 1].kind == TokenKind::blank && same(kept_, j + 2, x)) ||
         (!x && j + 1 == kept_.size()));
    const auto what = [](const Token& t) {
      return std::string(t.kind == TokenKind::comment ? "comment " : "") + quoted(t.text);
    };
    if (removed && !added) {
      add(Code::E7105, what(*x) + " removed" + in_col);
    } else if (added && !removed) {
      add(Code::E7104, what(*y) + " added");
    } else if (x && y) {
      add(Code::E7103, quoted(x->text) + " changed to " + quoted(y->text) + in_col);
    } else if (x) {
      add(Code::E7105,
          "the rest of the line " + quoted(in.text.substr(x->column - 1)) + " removed" + in_col);
    } else {
      add(Code::E7104, quoted(out.text.substr(y->column - 1)) + " added");
    }
  }

  // True when two comments differ only in S/F words (and blanks).
  bool comment_words_only(std::string_view a, std::string_view b) {
    auto inner = [](std::string_view c) {
      if (!c.empty() && (c.front() == '(' || c.front() == ';')) c.remove_prefix(1);
      if (!c.empty() && c.back() == ')') c.remove_suffix(1);
      return c;
    };
    // The comment's text without blanks, with or without its S/F words.
    auto rest = [](std::string_view text, std::vector<Token>& tokens, bool sf, std::string& out) {
      tokenize(text, tokens);
      out.clear();
      for (const auto& t : tokens)
        if ((sf || !t.is_sf()) && t.kind != TokenKind::blank) out += t.text;
    };
    rest(inner(a), ca_, true, sa_);
    rest(inner(b), cb_, true, sb_);
    if (sa_ == sb_) return false;  // only blanks differ
    rest(inner(a), ca_, false, sa_);
    rest(inner(b), cb_, false, sb_);
    return sa_ == sb_;
  }

  std::optional<int> speed_output_;
  bool siemens_;  // Sinumerik: a G4's S and F are its dwell time
  std::vector<Token> a_, b_, kept_, ca_, cb_;
  std::string sa_, sb_;
};

// True when the pair of lines holds no violation.
bool equivalent(LineComparer& comparer, const Line& in, const Line& out) {
  std::vector<Change> changes;
  ViolationSink scratch(0);
  comparer.compare(in, out, changes, scratch);
  return scratch.count() == 0;
}

// Streams through both texts line by line (nothing is kept but the
// current pair).
void compare_lines(std::string_view input, std::string_view output, const Options& options,
                   ChangeSink& changes, ViolationSink& sink) {
  LineComparer comparer(options.speed_output, options.dialect.kind == machines::Dialect::sinumerik);
  std::vector<Change> buffer;
  auto record = [&](const Line& x, const Line& y) {
    buffer.clear();
    comparer.compare(x, y, buffer, sink);
    for (auto& c : buffer) changes.add(std::move(c));
  };
  const std::uint32_t na = count_lines(input), nb = count_lines(output);
  std::size_t pa = 0, pb = 0;
  Line x, y;
  if (na == nb) {
    for (std::uint32_t k = 1; k <= na; ++k) {
      pa = line_at(input, pa, k, x);
      pb = line_at(output, pb, k, y);
      record(x, y);
    }
    return;
  }
  // Lines added or removed: the longest equal head and tail, the rest is
  // what was added, removed or replaced.
  const std::uint32_t n = std::min(na, nb);
  std::uint32_t head = 0;
  while (head < n) {
    const std::size_t next_a = line_at(input, pa, head + 1, x);
    const std::size_t next_b = line_at(output, pb, head + 1, y);
    if (!equivalent(comparer, x, y)) break;
    record(x, y);
    pa = next_a;
    pb = next_b;
    ++head;
  }
  std::uint32_t tail = 0;
  std::size_t ea = input.size(), eb = output.size();
  while (tail < n - head) {
    const std::size_t start_a = line_before(input, ea, na - tail, x);
    const std::size_t start_b = line_before(output, eb, nb - tail, y);
    if (!equivalent(comparer, x, y)) break;
    ea = start_a;
    eb = start_b;
    ++tail;
  }
  const std::uint32_t a_mid = na - head - tail, b_mid = nb - head - tail;
  const auto range = [](std::uint32_t first, std::uint32_t count) {
    return count == 1 ? "line " + std::to_string(first)
                      : "lines " + std::to_string(first) + ".." + std::to_string(first + count - 1);
  };
  std::string message;
  if (a_mid == 0)
    message = std::to_string(b_mid) + " line(s) added: output " + range(head + 1, b_mid);
  else if (b_mid == 0)
    message = std::to_string(a_mid) + " line(s) removed: input " + range(head + 1, a_mid);
  else
    message = "input " + range(head + 1, a_mid) + " became output " + range(head + 1, b_mid);
  message +=
      " (the input has " + std::to_string(na) + " lines, the output " + std::to_string(nb) + ")";
  sink.add(Code::E7101, head + 1, 1, head + 1, message);
  for (std::uint32_t k = 1; k <= tail; ++k) {
    ea = line_at(input, ea, na - tail + k, x);
    eb = line_at(output, eb, nb - tail + k, y);
    record(x, y);
  }
}

// Events of one program with SetSpindleSpeed/SetFeedRate left out, pulled
// one at a time.
class EventStream {
 public:
  EventStream(std::string_view text, const gcode::Dialect& dialect) : interpreter_(text, dialect) {}

  // The next event, or nullptr at the end. Throws GcodeError.
  const program::Event* next() {
    while (at_ >= events_.size()) {
      events_.clear();
      at_ = 0;
      if (done_ || !interpreter_.next(events_)) {
        done_ = true;
        return nullptr;
      }
      std::erase_if(events_, [](const program::Event& e) {
        return std::holds_alternative<program::SetSpindleSpeed>(e) ||
               std::holds_alternative<program::SetFeedRate>(e);
      });
    }
    return &events_[at_++];
  }

 private:
  gcode::Interpreter interpreter_;
  std::vector<program::Event> events_;
  std::size_t at_ = 0;
  bool done_ = false;
};

// The semantic proof: identical events but S/F, in the same order. Stops
// at the first difference (what follows no longer lines up).
void compare_events(std::string_view input, std::string_view output, const Options& options,
                    bool same_lines, const std::string& input_name, Result& result,
                    ViolationSink& sink) {
  EventStream a(input, options.dialect), b(output, options.dialect);
  while (true) {
    const program::Event* x = nullptr;
    try {
      x = a.next();
    } catch (const gcode::GcodeError& e) {
      throw vcpost::Error(e.code(), gcode::format(e.diagnostic(), input_name));
    }
    const program::Event* y = nullptr;
    try {
      y = b.next();
    } catch (const gcode::GcodeError& e) {
      const auto& d = e.diagnostic();
      sink.add(Code::E7123, d.line, d.column, x ? program::source_of(*x).line : 0,
               "the output does not interpret where the input does: " +
                   std::string(to_string(d.code)) + " " + d.message);
      return;
    }
    if (!x && !y) return;
    if (!x || !y) {
      const auto line = y ? program::source_of(*y).line : 0;
      sink.add(Code::E7122, line, y ? program::source_of(*y).column : 0,
               x ? program::source_of(*x).line : 0,
               y ? "the output has more events than the input, from " + event_text(*y)
                 : "the output ends before the input's " + event_text(*x));
      return;
    }
    if (program::is_motion(*x)) ++result.motions;
    if (!same_event(*x, *y, same_lines)) {
      const auto sy = program::source_of(*y);
      sink.add(Code::E7121, sy.line, sy.column, program::source_of(*x).line,
               "the output means " + event_text(*y) + " where the input means " + event_text(*x));
      return;
    }
  }
}

}  // namespace

Result verify_gcode(std::string_view input, std::string_view output, const Options& options,
                    const std::string& input_name) {
  Result result;
  result.kind = InputKind::gcode;
  ViolationSink sink(options.max_violations);
  // A line past the reader's limit, refused before either proof splits it
  // into tokens (a line of 200 MB held gigabytes of them): as the reader
  // refuses it in the input, as a violation in the output.
  const std::string too_long =
      "line longer than " + std::to_string(gcode::kMaxLineLength) + " bytes, the reader's limit";
  if (const std::uint32_t line = first_line_longer_than(input, gcode::kMaxLineLength)) {
    const gcode::Diagnostic d{vcpost::Code::E1006, line, 1, too_long};
    throw vcpost::Error(d.code, gcode::format(d, input_name));
  }
  if (const std::uint32_t line = first_line_longer_than(output, gcode::kMaxLineLength)) {
    sink.add(Code::E7123, line, 1, 0,
             "the output does not interpret where the input does: " +
                 std::string(to_string(vcpost::Code::E1006)) + " " + too_long);
    sink.move_into(result);
    return result;
  }
  ChangeSink changes(result, options.on_change);
  compare_lines(input, output, options, changes, sink);
  // The interpreted events carry their lines; with lines added or removed
  // only the order of events can be compared.
  const bool same_lines = sink.count_of(Code::E7101) == 0;
  ViolationSink semantic(options.max_violations);
  compare_events(input, output, options, same_lines, input_name, result, semantic);
  // The second proof's finding is news only on a line the first did not flag.
  for (const auto& v : semantic.violations())
    if (!sink.has_line(v.line)) sink.add(v.code, v.line, v.column, v.input_line, v.message);
  sink.move_into(result);
  return result;
}

}  // namespace vcpost::verify
