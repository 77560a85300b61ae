#include "postproc/cldata/cycle.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <string>
#include <vector>

#include "core/units.h"

namespace vcpost::cldata {

namespace {

using Vec = Eigen::Vector3d;

// One item of the record: a parameter, or a piece of one when a CAM system
// left the commas out ("25.000000 25.000000 DWELL" in CAMWorks).
struct Item {
  std::string_view text;
  double value = 0;
  bool is_number = false;
  std::uint32_t line = 0, column = 0;
};

bool parse_number(std::string_view t, double& v) {
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  if (t.empty()) return false;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  return r.ec == std::errc() && r.ptr == t.data() + t.size();
}

std::vector<Item> items_of(const ClRecord& r) {
  std::vector<Item> items;
  for (const ClParam& p : r.params) {
    if (p.is_number || p.text.find_first_of(" \t") == std::string_view::npos) {
      items.push_back({p.text, p.value, p.is_number, p.line, p.column});
      continue;
    }
    std::size_t at = 0;
    while (at < p.text.size()) {
      const std::size_t begin = p.text.find_first_not_of(" \t", at);
      if (begin == std::string_view::npos) break;
      std::size_t end = p.text.find_first_of(" \t", begin);
      if (end == std::string_view::npos) end = p.text.size();
      Item item{p.text.substr(begin, end - begin), 0, false, p.line,
                p.column + static_cast<std::uint32_t>(begin)};
      item.is_number = parse_number(item.text, item.value);
      items.push_back(item);
      at = end;
    }
  }
  return items;
}

bool is_word(const Item& item, std::string_view upper) {
  if (item.is_number || item.text.size() != upper.size()) return false;
  for (std::size_t i = 0; i < upper.size(); ++i) {
    if (std::toupper(static_cast<unsigned char>(item.text[i])) != upper[i]) return false;
  }
  return true;
}

class CycleParser {
 public:
  CycleParser(const ClRecord& r, double unit, std::string_view file)
      : record_(r), items_(items_of(r)), unit_(unit), file_(file) {}

  ClCycle parse() {
    kind();
    if (at_ < items_.size() && items_[at_].is_number) {
      positional();
    } else if (at_ < items_.size() &&
               (is_word(items_[at_], "G98") || is_word(items_[at_], "G99"))) {
      ++at_;  // CAMWorks: the return level is RTRCTO's anyway
      camworks();
    } else {
      couplets();
    }
    if (!has_depth_ || !has_feed_) {
      fail_record(Code::E3112,
                  "CYCLE/" + std::string(kind_text_) + " needs a depth (FEDTO) and a feed");
    }
    if (!has_clearance_) {
      fail_record(Code::E3112,
                  "CYCLE/" + std::string(kind_text_) + " needs RAPTO (where feeding starts)");
    }
    if (!(c_.feed > 0)) fail_record(Code::E3104, "cycle feed must be positive");
    if (c_.depth < 0 || c_.first_peck < 0 || c_.next_peck < 0 || c_.dwell_s < 0) {
      fail_record(Code::E3104, "cycle depth, pecks and dwell must not be negative");
    }
    if (c_.clearance < -c_.depth) {
      fail_record(Code::E3104, "cycle RAPTO lies below the bottom of the hole");
    }
    if (c_.retract && *c_.retract < c_.clearance) {
      fail_record(Code::E3104, "cycle RTRCTO lies below RAPTO");
    }
    if (c_.next_peck == 0) c_.next_peck = c_.first_peck;
    return c_;
  }

 private:
  [[noreturn]] void fail(Code code, const Item& item, std::string message) const {
    throw ClError(ClDiagnostic{code, item.line, item.column, std::move(message)}, file_);
  }
  [[noreturn]] void fail_record(Code code, std::string message) const {
    throw ClError(
        ClDiagnostic{code, record_.source.line, record_.source.column, std::move(message)}, file_);
  }

  const Item& item() const {
    if (at_ >= items_.size()) {
      throw ClError(ClDiagnostic{Code::E3104, record_.source.line, record_.source.column,
                                 "CYCLE/" + std::string(kind_text_) + " ends where a value is due"},
                    file_);
    }
    return items_[at_];
  }

  double number() {
    const Item& i = item();
    if (!i.is_number)
      fail(Code::E3104, i, "expected a number, found '" + std::string(i.text) + "'");
    ++at_;
    return i.value;
  }
  double length() { return number() * unit_; }

  // MMPM/IPM/MMPR/IPR: sets the factor and mode; false for other words.
  bool feed_word(const Item& i, double& factor) {
    if (is_word(i, "MMPM") || is_word(i, "MMPR")) {
      factor = 1.0;
    } else if (is_word(i, "IPM") || is_word(i, "IPR")) {
      factor = kMmPerInch;
    } else {
      return false;
    }
    c_.mode = is_word(i, "MMPR") || is_word(i, "IPR") ? program::FeedMode::per_revolution
                                                      : program::FeedMode::per_minute;
    return true;
  }

  void kind() {
    if (items_.empty()) fail_record(Code::E3104, "CYCLE needs a cycle word");
    const Item& k = items_[at_++];
    kind_text_ = k.text;
    if (is_word(k, "DRILL")) {
      c_.kind = CycleKind::drill;
      // NX and ICAM: DRILL,DEEP / DRILL,BRKCHP
      if (at_ < items_.size() && is_word(items_[at_], "DEEP")) {
        c_.kind = CycleKind::deep;
        ++at_;
      } else if (at_ < items_.size() && is_word(items_[at_], "BRKCHP")) {
        c_.kind = CycleKind::chip_break;
        ++at_;
      }
    } else if (is_word(k, "FACE")) {
      c_.kind = CycleKind::drill;
    } else if (is_word(k, "DEEP") || is_word(k, "DEEP2") || is_word(k, "PECK")) {
      c_.kind = CycleKind::deep;
    } else if (is_word(k, "BRKCHP")) {
      c_.kind = CycleKind::chip_break;
    } else if (is_word(k, "TAP")) {
      c_.kind = CycleKind::tap;
    } else if (is_word(k, "BORE") || is_word(k, "BORE5") || is_word(k, "REAM")) {
      c_.kind = CycleKind::bore;
    } else if (is_word(k, "BORE6")) {
      c_.kind = CycleKind::bore_stop;
    } else if (is_word(k, "BORE9")) {
      c_.kind = CycleKind::bore_dwell;
    } else {
      fail(Code::E3112, k,
           "CYCLE/" + std::string(k.text) +
               " is not a cycle vcpost posts (DRILL, FACE, DEEP, DEEP2, PECK, BRKCHP, TAP, BORE, "
               "BORE5, BORE6, BORE9, REAM)");
    }
    if (at_ < items_.size() && (c_.kind == CycleKind::bore) && is_word(items_[at_], "BACK")) {
      fail(Code::E3112, items_[at_],
           "CYCLE/BORE,BACK (back boring, G87) is not posted: it needs the spindle oriented "
           "and the tool shifted, which the CL data do not give");
    }
  }

  // CYCLE/DRILL, depth, MMPM|IPM|MMPR|IPR, feed, clearance[, retract]
  void positional() {
    c_.depth = length();
    has_depth_ = true;
    double factor = unit_;
    if (!feed_word(item(), factor)) {
      fail(Code::E3112, item(),
           "positional CYCLE/" + std::string(kind_text_) +
               " must be depth, MMPM|IPM|MMPR|IPR, feed, clearance[, retract]");
    }
    ++at_;
    c_.feed = number() * factor;
    has_feed_ = true;
    c_.clearance = length();
    has_clearance_ = true;
    if (at_ < items_.size()) c_.retract = length();
    if (at_ < items_.size()) fail(Code::E3112, items_[at_], "extra cycle value");
  }

  // CAMWorks: depth[,PECKING,first,next],feed word,feed,clearance,retract[ retract][ DWELL,t]
  void camworks() {
    c_.depth = length();
    has_depth_ = true;
    if (at_ < items_.size() && is_word(items_[at_], "PECKING")) {
      ++at_;
      c_.first_peck = length();
      c_.next_peck = length();
      if (c_.kind == CycleKind::drill) c_.kind = CycleKind::deep;
    }
    double factor = unit_;
    if (!feed_word(item(), factor)) {
      fail(Code::E3112, item(), "expected MMPM, IPM, MMPR or IPR");
    }
    ++at_;
    c_.feed = number() * factor;
    has_feed_ = true;
    c_.clearance = length();
    has_clearance_ = true;
    c_.retract = length();
    // CAMWorks repeats the retract level (its initial plane): accepted when equal.
    if (at_ < items_.size() && items_[at_].is_number) {
      const Item& again = items_[at_];
      if (std::abs(number() * unit_ - *c_.retract) > 1e-9) {
        fail(Code::E3112, again,
             "second retract level '" + std::string(again.text) +
                 "' differs from the first: which one the tool returns to is not known");
      }
    }
    couplets();
  }

  void couplets() {
    while (at_ < items_.size()) {
      const Item& w = items_[at_];
      double factor = unit_;
      if (is_word(w, "FEDTO") || is_word(w, "DEPTH")) {
        ++at_;
        c_.depth = length();
        has_depth_ = true;
      } else if (is_word(w, "RAPTO")) {
        ++at_;
        c_.clearance = length();
        has_clearance_ = true;
      } else if (is_word(w, "RTRCTO")) {
        ++at_;
        if (is_word(item(), "AUTO")) {
          ++at_;
          c_.retract.reset();
        } else {
          c_.retract = length();
        }
      } else if (is_word(w, "DWELL")) {
        ++at_;
        if (is_word(item(), "REV")) {
          fail(Code::E3112, item(), "DWELL,REV in a cycle is not posted (give seconds)");
        }
        c_.dwell_s = number();
      } else if (is_word(w, "STEP")) {
        ++at_;
        c_.first_peck = length();
        if (at_ < items_.size() && items_[at_].is_number) c_.next_peck = length();
        if (c_.kind == CycleKind::drill) c_.kind = CycleKind::deep;
      } else if (is_word(w, "1STPECK")) {
        ++at_;
        c_.first_peck = length();
      } else if (is_word(w, "SUBPECK")) {
        ++at_;
        c_.next_peck = length();
      } else if (feed_word(w, factor)) {
        ++at_;
        c_.feed = number() * factor;
        has_feed_ = true;
      } else {
        fail(Code::E3112, w,
             "CYCLE/" + std::string(kind_text_) + "," + std::string(w.text) +
                 " is not understood (FEDTO, RAPTO, RTRCTO, DWELL, STEP, 1STPECK, SUBPECK and "
                 "MMPM/IPM/MMPR/IPR are)");
      }
    }
  }

  const ClRecord& record_;
  std::vector<Item> items_;
  double unit_;
  std::string_view file_;
  std::size_t at_ = 0;
  std::string_view kind_text_;
  ClCycle c_;
  bool has_depth_ = false, has_feed_ = false, has_clearance_ = false;
};

}  // namespace

ClCycle parse_cycle(const ClRecord& record, double mm_per_unit, std::string_view file_name) {
  return CycleParser(record, mm_per_unit, file_name).parse();
}

std::optional<int> canned_code(const ClCycle& c, program::SpindleDirection direction) {
  const bool dwell = c.dwell_s > 0;
  switch (c.kind) {
    case CycleKind::drill:
      return dwell ? 82 : 81;
    case CycleKind::deep:
    case CycleKind::chip_break:
      if (c.first_peck == 0) return dwell ? 82 : 81;  // one stroke
      if (dwell || c.next_peck != c.first_peck) return std::nullopt;
      return c.kind == CycleKind::deep ? 83 : 73;
    case CycleKind::tap:
      if (direction != program::SpindleDirection::clockwise) return std::nullopt;
      return 84;
    case CycleKind::bore:
      return dwell ? 89 : 85;
    case CycleKind::bore_stop:
      return 86;
    case CycleKind::bore_dwell:
      return 89;
  }
  return std::nullopt;
}

void expand_cycle(const ClCycle& c, const Vec& hole, const Vec& from,
                  program::SpindleDirection direction, const program::SourceRef& src,
                  std::deque<program::Event>& out) {
  using program::StraightFeed;
  using program::StraightTraverse;
  const double top_z = hole.z() + c.retract.value_or(c.clearance);
  const double clear_z = hole.z() + c.clearance;
  const double bottom_z = hole.z() - c.depth;
  const auto at = [&](double z) { return Vec(hole.x(), hole.y(), z); };
  const Vec top = at(top_z), clear = at(clear_z), bottom = at(bottom_z);

  Vec p = from;
  const auto rapid = [&](const Vec& q) {
    out.push_back(StraightTraverse{p, q, src});
    p = q;
  };
  const auto feed = [&](const Vec& q) {
    out.push_back(StraightFeed{p, q, src});
    p = q;
  };
  const auto dwell = [&] {
    if (c.dwell_s > 0) out.push_back(program::Dwell{c.dwell_s, src});
  };
  // Up first when below the return level, never diagonally into the part.
  if (p.z() < top_z) rapid(Vec(p.x(), p.y(), top_z));
  rapid(top);
  if (clear_z != top_z) rapid(clear);

  switch (c.kind) {
    case CycleKind::drill:
      feed(bottom);
      dwell();
      break;
    case CycleKind::deep:
    case CycleKind::chip_break: {
      double peck = c.first_peck;
      double level = clear_z;
      while (true) {
        const double next = peck > 0 ? std::max(level - peck, bottom_z) : bottom_z;
        feed(at(next));
        if (next <= bottom_z) break;
        if (c.kind == CycleKind::deep) {
          rapid(clear);
          rapid(at(next + peck_clearance_mm));
        } else {
          rapid(at(next + peck_clearance_mm));
        }
        level = next;
        peck = c.next_peck;
      }
      dwell();
      break;
    }
    case CycleKind::tap: {
      // As rs274's G84: stop, reverse, dwell, out, stop, forward again.
      const auto reverse = direction == program::SpindleDirection::clockwise
                               ? program::SpindleDirection::counterclockwise
                               : program::SpindleDirection::clockwise;
      feed(bottom);
      out.push_back(program::SpindleOff{src});
      out.push_back(program::SpindleOn{reverse, src});
      dwell();
      feed(clear);
      out.push_back(program::SpindleOff{src});
      out.push_back(program::SpindleOn{direction, src});
      break;
    }
    case CycleKind::bore:
      feed(bottom);
      if (c.dwell_s > 0) {  // G89
        dwell();
        feed(clear);
        break;
      }
      // G85 as rs274 makes it: out to R at the feed, then a rapid to the
      // return level even where that is R (a move of no length).
      feed(clear);
      rapid(top);
      return;
    case CycleKind::bore_stop:
      feed(bottom);
      dwell();
      out.push_back(program::SpindleOff{src});
      rapid(top);
      out.push_back(program::SpindleOn{direction, src});
      return;
    case CycleKind::bore_dwell:
      feed(bottom);
      dwell();
      feed(clear);
      break;
  }
  if (p != top) rapid(top);
}

}  // namespace vcpost::cldata
