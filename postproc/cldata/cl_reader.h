// APT CL data -> motion events (postproc/program/events.h), streaming.
//
// Records and what they become (units: the file's UNITS, converted to mm;
// feeds to mm/min or mm/rev; positions are the CL points as written, in the
// CL file's output frame: MSYS/CSYS are recorded, not applied):
//   GOTO/x,y,z[,i,j,k] (several points per record, and Creo's bare
//       coordinate lines after it)      StraightFeed, or StraightTraverse
//                                        after RAPID (one motion record)
//   FROM/x,y,z                           start position, no event
//   GODLTA/dx,dy,dz | GODLTA/d           relative move (d along the axis)
//   CIRCLE|MOVARC/xc,yc,zc,i,j,k[,r,...] then GOTO: ArcFeed (axis +-X/Y/Z,
//       counterclockwise about i,j,k in APT/Creo's 7-value and SolidWorks'
//       6-value forms, clockwise in NX's 11-value form (8 or more values),
//       xc,yc,zc,r about +Z; a tilted circle becomes lines within
//       chord_tolerance). Start and end must lie on the circle within
//       arc_tolerance (E3109).
//   NURBS/ KNOT/ CNTRL/ (NX)             StraightFeeds within chord_tolerance
//   FEDRAT/f[,unit] | /unit,f            SetFeedRate (when it changes)
//   SPINDL/ value, RPM|SMM|SFM, CLW|CCLW, ON|OFF in any order
//                                        SetSpindleSpeed, SpindleOn/Off
//                                        (SMM/SFM -> rpm with the cutter)
//   CUTTER/1..7 values, TLDATA/MILL, Creo's `$$-> CUTTER / d`
//                                        cutter() (no event)
//   LOADTL/n, LOAD/TOOL,n                ChangeTool; SELECT/TOOL,n SelectTool
//   COOLNT, CUTCOM, DELAY, STOP, OPSTOP  Coolant, CutterCompensation, Dwell,
//                                        ProgramStop
//   PPRINT, PARTNO, INSERT, TOOL PATH    Message (INSERT is not copied to
//                                        the output program verbatim)
//   FINI (or the end after END-OF-PATH)  ProgramEnd
//   CYCLE/DRILL with FEDTO, RAPTO, [RTRCTO], feed, [DWELL] (distances
//       along the tool axis from each GOTO point): expanded to rapid, feed,
//       dwell, rapid; other cycles (DEEP, TAP, BORE ...) are refused (E3112).
//   UNITS|UNIT, TLAXIS, MULTAX           state; any axis other than +Z is
//                                        refused (E3108): events are 3-axis
//   PAINT, MACHIN, MSYS, CSYS, TRNTYP, TPRINT, TOOLNO, CLRSRF, END,
//   END-OF-PATH, $$ comments             ignored
//   APT source statements (TLON, GOFWD, INDIRV, `X=...` definitions)
//                                        refused (E3113)
//   any other record                     ignored with warning W3150 (once
//                                        per word)
// The position before the first move is unknown unless FROM gives it: the
// first move's start is then its own end.
#pragma once

#include <deque>
#include <istream>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "postproc/cldata/cl_codes.h"
#include "postproc/cldata/cutter.h"
#include "postproc/cldata/record_reader.h"
#include "postproc/program/events.h"

namespace vcpost::cldata {

struct ClReadOptions {
  ClLexOptions lex;
  double chord_tolerance = 0.001;  // mm: NURBS and tilted arcs as lines
  double arc_tolerance = 0.005;    // mm: allowed |r_start - r_end| (and vs a given r)
  double axis_tolerance = 1e-6;    // tool axis unit-vector difference taken as +Z
};

class ClReader {
 public:
  // `in` must outlive the reader; file_name appears in diagnostics only.
  ClReader(std::istream& in, std::string file_name, ClReadOptions options = {});

  // The next event, or nullopt after the last one. Throws ClError for input
  // that cannot be converted soundly (codes in cl_codes.h).
  std::optional<program::Event> next();

  // Warnings met so far (W31xx), in file order.
  const std::vector<ClDiagnostic>& warnings() const { return warnings_; }
  // Every cutter defined so far, in file order (a handful per program).
  const std::vector<ClCutter>& cutters() const { return cutters_; }
  const std::string& file_name() const { return lexer_.file_name(); }
  std::uint64_t record_count() const { return records_; }
  // MSYS/CSYS seen with a non-identity frame (reported, not applied).
  bool saw_rotated_frame() const { return rotated_frame_; }

 private:
  struct Arc {
    Eigen::Vector3d centre;
    Eigen::Vector3d axis;
    std::optional<double> radius;
    program::SourceRef source;
  };
  struct Cycle {
    double depth = 0;
    double rapto = 0;
    std::optional<double> rtrcto;
    double feed = 0;
    program::FeedMode mode = program::FeedMode::per_minute;
    double dwell = 0;
  };
  struct Feed {
    double rate;
    program::FeedMode mode;
    bool operator==(const Feed&) const = default;
  };

  void process(const ClRecord& r);
  void process_motion_points(const ClRecord& r, bool continuation);
  void move_to(const Eigen::Vector3d& p, const program::SourceRef& src);
  void emit_arc(const Eigen::Vector3d& start, const Eigen::Vector3d& end, const Arc& arc,
                const program::SourceRef& src);
  void drill(const Eigen::Vector3d& p, const program::SourceRef& src);
  void set_feed(const Feed& f, const program::SourceRef& src);
  void finish_nurbs();
  void finish_input();

  void fedrat(const ClRecord& r);
  void spindl(const ClRecord& r);
  void cutter(const ClRecord& r);
  void tldata(const ClRecord& r);
  void creo_cutter_comment(const ClRecord& r);
  void circle(const ClRecord& r);
  void cycle(const ClRecord& r);
  void check_axis(const Eigen::Vector3d& axis, std::uint32_t line, std::uint32_t column);

  double number(const ClRecord& r, std::size_t i) const;
  int integer(const ClRecord& r, std::size_t i) const;
  bool word_is(const ClParam& p, std::string_view upper_word) const;
  void require_numbers(const ClRecord& r) const;
  [[noreturn]] void fail(ClCode code, std::uint32_t line, std::uint32_t column,
                         std::string message) const;
  [[noreturn]] void fail(ClCode code, const ClRecord& r, std::string message) const;
  [[noreturn]] void fail(ClCode code, const ClParam& p, std::string message) const;
  void warn(ClCode code, const program::SourceRef& src, std::string message);

  ClRecordReader lexer_;
  ClReadOptions options_;
  ClRecord record_;
  std::deque<program::Event> queue_;
  std::vector<ClDiagnostic> warnings_;
  std::vector<ClCutter> cutters_;
  std::set<std::string, std::less<>> unknown_words_;
  std::uint64_t records_ = 0;

  double unit_ = 1.0;  // mm per file length unit
  std::optional<Eigen::Vector3d> position_;
  bool multax_ = false;
  bool rotated_frame_ = false;

  // RAPID and CIRCLE apply to the next GOTO record and its continuation lines.
  bool rapid_pending_ = false;
  bool rapid_active_ = false;
  std::optional<Arc> arc_pending_;
  std::optional<Arc> arc_active_;
  bool in_goto_ = false;  // the last statement was GOTO (continuation lines allowed)

  std::optional<Feed> program_feed_;  // last FEDRAT
  std::optional<Feed> machine_feed_;  // last SetFeedRate emitted
  double rpm_ = 0;
  program::SpindleDirection direction_ = program::SpindleDirection::clockwise;
  std::optional<Cycle> cycle_;
  std::optional<Cycle> last_cycle_;

  bool nurbs_active_ = false;
  bool nurbs_rapid_ = false;
  program::SourceRef nurbs_source_;
  std::vector<double> knots_;
  std::vector<Eigen::Vector4d> cntrl_;
  std::vector<Eigen::Vector3d> scratch_;

  bool ended_ = false;           // FINI seen
  bool end_of_path_ = false;     // the last statement was END-OF-PATH
  bool input_done_ = false;
  program::SourceRef last_source_;
};

}  // namespace vcpost::cldata
