// The interpreter's own: what its files share (interpreter.cpp, the block
// transaction; interpreter_words.cpp, the words; interpreter_moves.cpp,
// interpreter_approach.cpp, interpreter_functions.cpp, interpreter_flow.cpp,
// interpreter_cycles.cpp, interpreter_plane.cpp, the handlers): a block's
// words as the handlers read them (Interpreter::Words), the families of
// words a block kind takes, the M functions the reader follows, and the
// plane geometry of the contour. Not for other modules.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "postproc/heidenhain/approach.h"
#include "postproc/heidenhain/interpreter.h"
#include "postproc/program/events.h"

namespace vcpost::heidenhain {

// The parameter banks, one after another in Interpreter::q_: Q0-1999,
// QL0-499, QR0-499.
inline constexpr std::size_t kQ = 2000, kQL = 500, kQR = 500;

// Words a block kind takes (bits of Words::allowed).
enum Allow : std::uint32_t {
  a_xyz = 1u << 0,     // X Y Z IX IY IZ
  a_abc = 1u << 1,     // A B C IA IB IC
  a_polar = 1u << 2,   // PA IPA PR IPR
  a_dr = 1u << 3,      // DR+ DR-
  a_r = 1u << 4,       // R (radius, CR RND)
  a_comp = 1u << 5,    // R0 RL RR R+ R-
  a_feed = 1u << 6,    // F FMAX FAUTO FQ
  a_m = 1u << 7,       // M (and MB after M140)
  a_normal = 1u << 8,  // NX NY NZ TX TY TZ (LN)
  a_chf = 1u << 9,     // CHF's length
  a_link = 1u << 10,   // LEN CCA (APPR, DEP)
};

// The M functions the reader follows; every other one passes with a warning.
enum class MAction {
  stop,
  optional_stop,
  end,
  spindle_cw,
  spindle_ccw,
  spindle_off,
  mist,
  flood,
  coolant_off,
  cw_coolant,
  ccw_coolant,
  machine_frame,
  cycle_call,
  tcpm_on,
  tcpm_off,
  retract,
  quiet,
  refused,
  passed
};

inline Eigen::Vector2d xy(const Eigen::Vector3d& p) { return {p.x(), p.y()}; }

// Direction of an arc's tangent at `p` (unit, XY), rotation +1 ccw.
inline Eigen::Vector2d arc_tangent(const Eigen::Vector2d& centre, const Eigen::Vector2d& p,
                                   int rotation) {
  const Eigen::Vector2d radial = (p - centre).normalized();
  const Eigen::Vector2d t = left_normal(radial);
  return rotation > 0 ? t : Eigen::Vector2d(-t);
}

// The words of a motion block, evaluated (program units; feeds as written).
struct Interpreter::Words {
  std::array<std::optional<double>, 3> axis, inc;     // X Y Z, IX IY IZ
  std::array<std::optional<double>, 3> rot, rot_inc;  // A B C, IA IB IC
  std::optional<double> pa, ipa, pr, ipr, r, chf, len, cca;
  std::array<std::optional<double>, 6> normal;  // NX NY NZ TX TY TZ
  int dr = 0;
  std::optional<program::CompensationSide> comp;
  bool fmax = false;
  std::optional<double> feed;  // program units
  bool fauto = false;
  bool mb_max = false;
  std::optional<double> mb;
  struct M {
    long number;
    MAction action;
    std::uint32_t at;
  };
  std::vector<M> m;
  std::uint32_t first_word = 0;
  bool has(MAction a) const {
    return std::any_of(m.begin(), m.end(), [a](const M& x) { return x.action == a; });
  }
  bool any_xyz() const {
    return std::any_of(axis.begin(), axis.end(), [](auto& v) { return v.has_value(); }) ||
           std::any_of(inc.begin(), inc.end(), [](auto& v) { return v.has_value(); });
  }
};

}  // namespace vcpost::heidenhain
