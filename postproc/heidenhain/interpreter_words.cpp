// A block's words read into Interpreter::Words, each by its family, and the
// values they hold: numbers, or Q, QL and QR parameters read from q_.
#include "postproc/heidenhain/interpreter_words.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "postproc/heidenhain/interpreter.h"

namespace vcpost::heidenhain {

namespace {

MAction m_action(long m) {
  switch (m) {
    case 0:
      return MAction::stop;
    case 1:
      return MAction::optional_stop;
    case 2:
    case 30:
      return MAction::end;
    case 3:
      return MAction::spindle_cw;
    case 4:
      return MAction::spindle_ccw;
    case 5:
      return MAction::spindle_off;
    case 7:
      return MAction::mist;
    case 8:
      return MAction::flood;
    case 9:
      return MAction::coolant_off;
    case 13:
      return MAction::cw_coolant;
    case 14:
      return MAction::ccw_coolant;
    case 91:
    case 92:
      return MAction::machine_frame;
    case 99:
      return MAction::cycle_call;
    case 128:
      return MAction::tcpm_on;
    case 129:
      return MAction::tcpm_off;
    case 140:
      return MAction::retract;
    case 94:
    case 126:
    case 127:
      return MAction::quiet;  // rotary display and path: no move here
    case 89:                  // modal cycle call
    case 103:                 // plunging feed factor
    case 136:                 // feed per revolution
      return MAction::refused;
    default:
      return MAction::passed;
  }
}

}  // namespace

std::size_t Interpreter::parameter_index(const Value& v, std::uint32_t at) const {
  const auto n = static_cast<std::size_t>(v.number);
  std::size_t index = n;
  switch (v.bank) {
    case Value::Bank::q:
      if (n >= kQ) fail(Code::E3309, at, "Q parameters run from Q0 to Q1999");
      break;
    case Value::Bank::ql:
      if (n >= kQL) fail(Code::E3309, at, "QL parameters run from QL0 to QL499");
      index = kQ + n;
      break;
    case Value::Bank::qr:
      if (n >= kQR) fail(Code::E3309, at, "QR parameters run from QR0 to QR499");
      index = kQ + kQL + n;
      break;
    case Value::Bank::literal:
      fail(Code::E3309, at, "a Q parameter is expected here");
  }
  return index;
}

double Interpreter::value(const Value& v, std::uint32_t at) const {
  if (!v.is_parameter()) return v.number;
  const double q = q_[parameter_index(v, at)];
  return v.negate ? -q : q;
}

// read_words' reader: each word into Words by its family (axes, vectors,
// dimensions, contour words, feeds, M functions); a family's reader answers
// false for a word of another family, and a word of none, or of a family
// the block kind does not take, is refused.
struct Interpreter::WordReader {
  const Interpreter& in;
  std::uint32_t allowed;
  Words& w;
  bool radius_taken = false;  // R read as a radius: a second R is R0 or refused

  void read(const Word& word) {
    if (w.first_word == 0) w.first_word = word.begin;
    if (!axis_word(word) && !vector_word(word) && !dimension_word(word) && !contour_word(word) &&
        !feed_word(word) && !m_word(word))
      refuse(word);
  }

  std::string text(const Word& word) const {
    return std::string(in.block_.text.substr(word.begin, word.end - word.begin));
  }
  [[noreturn]] void refuse(const Word& word) const {
    in.fail(Code::E3307, word.begin,
            "'" + text(word) + "' is no word of " + std::string(in.block_.keyword) + " blocks");
  }
  void expect(const Word& word, std::uint32_t family) const {
    if (!(allowed & family)) refuse(word);
  }
  double value(const Word& word) const {
    if (!word.has_value) in.fail(Code::E3303, word.begin, "'" + text(word) + "' needs a value");
    return in.value(word.value, word.begin);
  }
  bool take(const Word& word, std::uint32_t family, std::optional<double>& into) const {
    expect(word, family);
    into = value(word);
    return true;
  }

  // X Y Z IX IY IZ, A B C IA IB IC: absolute and incremental positions.
  bool axis_word(const Word& word) {
    switch (word.key) {
      case name("X"):
      case name("Y"):
      case name("Z"):
      case name("IX"):
      case name("IY"):
      case name("IZ"): {
        expect(word, a_xyz);
        const bool inc = (word.key >> 8) == 'I';
        const int axis = static_cast<int>(word.key & 0xff) - 'X';
        (inc ? w.inc : w.axis)[static_cast<std::size_t>(axis)] = value(word);
        return true;
      }
      case name("A"):
      case name("B"):
      case name("C"):
      case name("IA"):
      case name("IB"):
      case name("IC"): {
        expect(word, a_abc);
        const bool inc = (word.key >> 8) == 'I';
        const int axis = static_cast<int>(word.key & 0xff) - 'A';
        (inc ? w.rot_inc : w.rot)[static_cast<std::size_t>(axis)] = value(word);
        return true;
      }
      default:
        return false;
    }
  }

  // NX NY NZ TX TY TZ: LN's surface normal and tool orientation.
  bool vector_word(const Word& word) {
    switch (word.key) {
      case name("NX"):
      case name("NY"):
      case name("NZ"):
      case name("TX"):
      case name("TY"):
      case name("TZ"): {
        expect(word, a_normal);
        const bool tool = (word.key >> 8) == 'T';
        const auto axis = static_cast<std::size_t>((word.key & 0xff) - 'X');
        w.normal[(tool ? 3 : 0) + axis] = value(word);
        return true;
      }
      default:
        return false;
    }
  }

  // PA IPA PR IPR (polar), LEN CCA (APPR, DEP), CHF's length.
  bool dimension_word(const Word& word) {
    switch (word.key) {
      case name("PA"):
        return take(word, a_polar, w.pa);
      case name("IPA"):
        return take(word, a_polar, w.ipa);
      case name("PR"):
        return take(word, a_polar, w.pr);
      case name("IPR"):
        return take(word, a_polar, w.ipr);
      case name("LEN"):
        return take(word, a_link, w.len);
      case name("CCA"):
        return take(word, a_link, w.cca);
      case name("CHF"):
        return take(word, a_chf, w.chf);
      default:
        return false;
    }
  }

  // DR+ DR- (an arc's direction), R (a radius, or R0 and R+ R-), RL RR.
  bool contour_word(const Word& word) {
    switch (word.key) {
      case name("DR"):
        if (!(allowed & a_dr) || word.has_value || word.sign == 0) refuse(word);
        w.dr = word.sign == '+' ? 1 : -1;
        return true;
      case name("R"):
        radius_or_compensation(word);
        return true;
      case name("RL"):
        expect(word, a_comp);
        w.comp = program::CompensationSide::left;
        return true;
      case name("RR"):
        expect(word, a_comp);
        w.comp = program::CompensationSide::right;
        return true;
      default:
        return false;
    }
  }

  // R: the block's radius (CR, RND; the first R with a value), else R0
  // (compensation off) or R+ / R- where compensation words are taken.
  void radius_or_compensation(const Word& word) {
    if ((allowed & a_r) && !radius_taken && word.has_value) {
      w.r = value(word);
      radius_taken = true;
    } else if ((allowed & a_comp) && word.has_value && !word.value.is_parameter() &&
               word.value.number == 0) {
      w.comp = program::CompensationSide::off;
    } else if ((allowed & a_comp) && !word.has_value && word.sign != 0) {
      // R+ / R-: paraxial lengthening; no side of the contour.
    } else {
      refuse(word);
    }
  }

  // F FMAX FAUTO; FU and FZ are refused.
  bool feed_word(const Word& word) {
    switch (word.key) {
      case name("F"):
        return take(word, a_feed, w.feed);
      case name("FMAX"):
        expect(word, a_feed);
        w.fmax = true;
        return true;
      case name("FAUTO"):
        expect(word, a_feed);
        w.fauto = true;
        return true;
      case name("FU"):
      case name("FZ"):
        in.fail(Code::E3319, word.begin,
                "feed per revolution or per tooth (FU, FZ) is not read: write F in mm/min");
      default:
        return false;
    }
  }

  // M (0-999, with its action) and M140's MB (a distance or MAX).
  bool m_word(const Word& word) {
    switch (word.key) {
      case name("M"): {
        expect(word, a_m);
        const double m = value(word);
        if (m < 0 || m != std::floor(m) || m > 999)
          in.fail(Code::E3303, word.begin, "M takes a whole number 0-999");
        const auto number = static_cast<long>(m);
        w.m.push_back({number, m_action(number), word.begin});
        return true;
      }
      case name("MB"):
        expect(word, a_m);
        if (word.sign == '*')
          w.mb_max = true;
        else
          w.mb = value(word);
        return true;
      default:
        return false;
    }
  }
};

Interpreter::Words Interpreter::read_words(std::uint32_t allowed) const {
  Words w;
  WordReader reader{*this, allowed, w};
  for (const Word& word : block_.words) reader.read(word);
  return w;
}

}  // namespace vcpost::heidenhain
