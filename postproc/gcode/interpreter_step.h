// The interpreter's own: what its files share (interpreter.cpp, the block
// transaction; interpreter_flow.cpp, subroutines, loops and branches;
// interpreter_sinumerik.cpp, Sinumerik's cycles): one block in execution
// (Interpreter::Step) and the small conversions its handlers use. Not for
// other modules.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/units.h"
#include "postproc/gcode/codes.h"
#include "postproc/gcode/interpreter.h"

namespace vcpost::gcode {

// A length or feed in the program's units, in mm (mm/min).
inline double to_mm(double v, bool inches) { return inches ? v * kMmPerInch : v; }

// A whole number in [0, 1e9]: T, H and arc turns, which become ints (a
// larger value would not fit, and its conversion would be undefined).
inline bool whole_number(double v) { return v >= 0 && v <= 1e9 && v == std::floor(v); }

inline std::string code_text(char letter, int tenths) {
  std::string s(1, letter);
  s += std::to_string(tenths / 10);
  if (tenths % 10 != 0) {
    s += '.';
    s += std::to_string(tenths % 10);
  }
  return s;
}

// The code of a G or M word found in its table, x10 (61.1 -> 611), as
// find_code() matched it.
inline int code_of(const Word& w) {
  const double tenths = w.value * 10.0;
  return static_cast<int>(tenths + (tenths < 0 ? -0.5 : 0.5));  // as lround: found codes are small
}

// The words of one block by letter and by modal group, as positions in
// Block::words plus one (0: none). Built afresh for every block: byte
// entries keep clearing it to a few stores (arrays of pointers, cleared
// with `rep stos`, took a fifth of the reading stage's time).
struct WordIndex {
  std::array<std::uint8_t, 26> by_letter{};
  std::array<std::uint8_t, kGroupCount> g{};
  std::array<std::uint8_t, kGroupCount> m{};
};
// A word is indexed only when none before it was refused: each letter once,
// one G per group, at most four M; so its position is below this bound.
inline constexpr std::size_t kMaxIndexedPosition = 26 + kGroupCount + 4;
static_assert(kMaxIndexedPosition < std::numeric_limits<std::uint8_t>::max());

inline program::SourceRef source(const Block& b, std::uint32_t column) {
  return program::SourceRef{b.line, column == 0 ? 1u : column, b.offset};
}

// One block in execution: its words indexed by letter and group, the modal
// state it builds (a copy, committed only when every handler has run), and
// what one handler leaves for a later one.
struct Interpreter::Step {
  Step(const Block& block, std::vector<program::Event>& out, const ModalState& before)
      : b(block), events(out), state(before) {}

  const Block& b;
  std::vector<program::Event>& events;
  ModalState state;
  WordIndex index;
  bool mist_and_flood = false;  // Fanuc M7 M8 in one block
  const Word* nonmodal = nullptr;
  int nonmodal_code = 0;
  const Word* dwell_x = nullptr;  // Fanuc G4 X: seconds, not an axis
  bool has_xyz = false;
  const Word* motion_word = nullptr;
  const Word* cycle_word = nullptr;  // Fanuc only
  int motion_code = -1;
  bool macro_call = false;     // G65 takes S, T, ... as macro arguments
  bool siemens_dwell = false;  // Sinumerik G4 F.. (seconds) or S.. (turns)
  bool speed_limit = false;    // Sinumerik G25/G26 S..: spindle limits
  // G93: the F event goes right before its move, with the path speed it
  // gives that move (rs274's order and figure).
  const Word* inverse_f = nullptr;
  std::optional<Origins> origins;  // the offsets when the block changes one
  Eigen::Vector3d offset_before = Eigen::Vector3d::Zero();
  Eigen::Vector3d offset_after = Eigen::Vector3d::Zero();
  bool axes_taken = false;   // the axis words are not a move (G10, G92, ...)
  bool frame_words = false;  // X Y Z I J K are G68.2's origin and angles
  bool has_axis = false;     // the block moves to its axis words
  std::uint32_t motion_column = 1;

  const Word* at(std::uint8_t slot) const __attribute__((always_inline)) {
    return slot == 0 ? nullptr : &b.words[slot - 1u];
  }
  const Word* word(char letter) const {
    return at(index.by_letter[static_cast<std::size_t>(letter - 'A')]);
  }
  const Word* g(Group group) const { return at(index.g[static_cast<std::size_t>(group)]); }
  const Word* m(Group group) const { return at(index.m[static_cast<std::size_t>(group)]); }
  // The code of a group's word; only for a group that has one.
  int g_code(Group group) const { return code_of(*g(group)); }
  int m_code(Group group) const { return code_of(*m(group)); }
  template <class E>
  void emit(E&& e) {
    events.emplace_back(std::forward<E>(e));
  }
  // path_rate() costs a square root or an arc length: asked only in G93.
  template <class PathRate>
  void emit_inverse_f(PathRate path_rate) {
    if (!inverse_f) return;
    emit(program::SetFeedRate{state.feed, program::FeedMode::inverse_time,
                              source(b, inverse_f->column), std::optional<double>(path_rate())});
    inverse_f = nullptr;
  }
  std::uint32_t first_axis_column(std::uint32_t fallback) const {
    std::uint32_t col = 0;
    for (char a : {'X', 'Y', 'Z'})
      if (const Word* w = word(a)) col = col == 0 ? w->column : std::min(col, w->column);
    return col == 0 ? fallback : col;
  }
};

}  // namespace vcpost::gcode
