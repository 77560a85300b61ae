// APT CL data -> motion events (postproc/program/events.h), streaming.
//
// Records and what they become (units: the file's UNITS, converted to mm;
// feeds to mm/min or mm/rev; positions are the CL points in the CL file's
// output frame, moved only by a CSYS, see below):
//   GOTO/x,y,z[,i,j,k] (several points per record, and Creo's bare
//       coordinate lines after it)      StraightFeed, or StraightTraverse
//                                        after RAPID (one motion record)
//   FROM/x,y,z                           start position, no event
//   GODLTA/dx,dy,dz | GODLTA/d           relative move (d along the axis)
//   CIRCLE|MOVARC/xc,yc,zc,i,j,k[,r,...] then GOTO: ArcFeed (axis +-X/Y/Z,
//       counterclockwise about i,j,k in APT/Creo's 7-value and SolidWorks'
//       6-value forms, clockwise in NX's 11-value form (8 or more values),
//       xc,yc,zc,r about +Z; NX's TIMES,n adds n full turns, written as
//       n full circles before the arc; a tilted circle becomes lines within
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
//       (a preselection: SolidWorks CAM selects the next tool while the
//       one in the spindle still cuts, so SELECT alone changes nothing)
//   TOOLNO/n[,...]                       the number of the next tool change:
//       CATIA writes LOADTL after it (then that is the change); with no
//       LOAD/TOOL or LOADTL before the next motion, ChangeTool n there
//   a cutter record (CUTTER, TLDATA, after NX's TOOL PATH) after the
//       section's first motion that describes another cutter than the
//       section's (CAMWorks and NX write no LOAD/TOOL when the operation
//       has no tool number): ChangeTool before the next motion, unless a
//       LOAD/TOOL or LOADTL comes first, to the tool TOOLNO or SELECT/TOOL
//       named since the last change; with no number, refused (E3120): the
//       output cannot write a tool change without one
//   COOLNT, CUTCOM (LEFT|RIGHT|OFF[,XYPLAN][,register]; CAMWorks' ON),
//   DELAY (seconds or REV,n), STOP, OPSTOP
//                                        Coolant, CutterCompensation, Dwell,
//                                        ProgramStop
//   PPRINT, PARTNO, INSERT, TOOL PATH, OPFEATSTART, OPFEATEND, OPSKIP, MFGNO
//                                        Message (a comment in the output)
//   FINI (or the end after END-OF-PATH)  ProgramEnd
//   CYCLE/DRILL, FACE, DEEP, DEEP2, PECK, BRKCHP, TAP, BORE, BORE5, BORE6,
//       BORE9, REAM (cycle.h): each GOTO while a cycle is on is a hole,
//       expanded into the moves of the matching canned cycle; CYCLE/OFF
//       ends it (INIT, CLEAR and CAMWorks' ON around it); others refused (E3112).
//   UNITS|UNIT, TLAXIS, MULTAX           state; any axis other than +Z is
//                                        refused (E3108): events are 3-axis
//   CSYS/r11,r12,r13,tx,r21,r22,r23,ty,r31,r32,r33,tz (the 3x4 matrix row
//       by row), until the next CSYS. A translation and a rotation about Z
//       (R's third row and column 0,0,1 within 1e-6): the frame the
//       following points are given in; each point p becomes R p + t
//       (directions R d: GODLTA, circle axes). Any other rotation: a tilted
//       working plane (3+2), WorkingFrame{R, t}; the points and axes that
//       follow are in the base frame (SolidWorks CAM, docs/cldata.md), the
//       events in the frame's coordinates R^T (p - t), and every tool axis
//       must be R's z (E3108 otherwise). A mirror or a scaling is refused
//       (E3119).
//   MSYS (NX: the output frame, the GOTOs are in it), TRNTYP/WORLD,
//   ORIGIN that leave the points where they are (identity), ROTABL by 0
//                                        accepted; another TRNTYP or ORIGIN
//                                        is refused (E3119), a turned table
//                                        too (E3108)
//   $$ comment records                   Message (a comment in the output)
//   PAINT, MACHIN, TPRINT, CLRSRF, END, MODE, SEQNO, BOX,
//   CSI_SET_FLUTE_LENGTH, CSI_SET_EXTENSION_LENGTH, END-OF-PATH
//                                        no motion, no state: ignored
//   APT source statements (TLON, GOFWD, INDIRV, `X=...` definitions)
//                                        refused (E3113); TRACUT, GOHOME
//                                        refused (E3117)
//   any other record                     refused (E3118) with its text: a
//                                        record not understood may move the
//                                        tool
// Records are dispatched from one table, word -> handler (find_rule).
// The position before the first move is unknown unless FROM gives it: the
// first move's start is then its own end.
#pragma once

#include <Eigen/Core>
#include <deque>
#include <istream>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "postproc/cldata/cl_codes.h"
#include "postproc/cldata/cutter.h"
#include "postproc/cldata/cycle.h"
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

 private:
  struct Arc {
    Eigen::Vector3d centre;
    Eigen::Vector3d axis;
    std::optional<double> radius;
    int turns = 0;  // NX's TIMES,n: full turns before the arc's own sweep
    program::SourceRef source;
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

  // One handler per record family, found by the record's word (find_rule).
  using Handler = void (ClReader::*)(const ClRecord&);
  struct RecordRule {
    std::string_view word;
    Handler handler;
  };
  static const RecordRule* find_rule(std::string_view word);
  void rapid(const ClRecord& r);
  void from(const ClRecord& r);
  void godlta(const ClRecord& r);
  void loadtl(const ClRecord& r);
  void toolno(const ClRecord& r);
  void tool_changed(int number);
  void note_cutter(const ClRecord& r);
  std::vector<double> cutter_values(const ClRecord& r, std::size_t first, std::size_t last) const;
  void add_cutter(ClCutter c, const ClRecord& r, std::string_view what);
  void begin_motion(const program::SourceRef& src);
  void load_or_select(const ClRecord& r);
  void units(const ClRecord& r);
  void coolnt(const ClRecord& r);
  void cutcom(const ClRecord& r);
  void delay(const ClRecord& r);
  void stop(const ClRecord& r);
  void fini(const ClRecord& r);
  void end_of_path(const ClRecord& r);
  void message(const ClRecord& r);
  void comment(const ClRecord& r);
  void tlaxis(const ClRecord& r);
  void multax(const ClRecord& r);
  void nurbs(const ClRecord& r);
  void nurbs_data(const ClRecord& r);
  void msys(const ClRecord& r);
  void csys(const ClRecord& r);
  void trntyp(const ClRecord& r);
  void origin(const ClRecord& r);
  void rotabl(const ClRecord& r);
  [[noreturn]] void tracut(const ClRecord& r);
  [[noreturn]] void gohome(const ClRecord& r);
  [[noreturn]] void apt_source(const ClRecord& r);
  void ignore(const ClRecord& r);
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
  [[noreturn]] void fail(Code code, std::uint32_t line, std::uint32_t column,
                         std::string message) const;
  [[noreturn]] void fail(Code code, const ClRecord& r, std::string message) const;
  [[noreturn]] void fail(Code code, const ClParam& p, std::string message) const;
  void warn(Code code, const program::SourceRef& src, std::string message);

  ClRecordReader lexer_;
  ClReadOptions options_;
  ClRecord record_;
  std::deque<program::Event> queue_;
  std::vector<ClDiagnostic> warnings_;
  std::vector<ClCutter> cutters_;
  std::uint64_t records_ = 0;

  double unit_ = 1.0;    // mm per file length unit
  bool multax_ = false;  // GOTO records carry the tool axis (i, j, k)
  std::optional<Eigen::Vector3d> position_;
  program::SourceRef last_source_;

  // The last CSYS: points p are placed at rotation p + offset (mm), in the
  // coordinates of `frame` (a tilted CSYS's; identity otherwise).
  struct Csys {
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
    program::WorkingFrame frame;
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // the tool axis as the file gives it
  };
  Csys csys_;
  Eigen::Vector3d place(const Eigen::Vector3d& p) const {
    return csys_.rotation * p + csys_.offset;
  }

  // RAPID and CIRCLE apply to the next GOTO record and its continuation lines.
  struct NextMotion {
    bool rapid_pending = false;
    bool rapid_active = false;
    std::optional<Arc> arc_pending;
    std::optional<Arc> arc_active;
    bool in_goto = false;  // the last statement was GOTO (continuation lines allowed)
  };
  NextMotion next_motion_;

  struct Feeds {
    std::optional<Feed> programmed;  // last FEDRAT
    std::optional<Feed> emitted;     // last SetFeedRate emitted
  };
  Feeds feed_;
  struct Spindle {
    double rpm = 0;
    program::SpindleDirection direction = program::SpindleDirection::clockwise;
  };
  Spindle spindle_;

  // Tool changes the CL data make without LOAD/TOOL or LOADTL.
  struct NewCutter {
    std::string record;  // "CUTTER/6,3"
    std::uint32_t line = 0, column = 0;
  };
  struct Tool {
    std::optional<int> in_spindle;              // the last ChangeTool's
    std::optional<int> named;                   // TOOLNO or SELECT/TOOL since the last change
    bool toolno_pending = false;                // TOOLNO since the last motion or change
    bool moved = false;                         // a motion since the last change
    std::optional<std::size_t> section_cutter;  // cutters_ index: the section's cutter
    std::optional<NewCutter> new_cutter;        // a cutter record of another tool since
  };
  Tool tool_;

  struct Cycles {
    std::optional<ClCycle> active;  // CYCLE/ on: each GOTO is a hole
    std::optional<ClCycle> last;    // the last CYCLE/<kind>: CYCLE/ON resumes it
  };
  Cycles cycle_;

  // NX's NURBS/ KNOT/ CNTRL/ records, collected until the curve ends.
  struct NurbsInput {
    bool active = false;
    bool rapid = false;
    program::SourceRef source;
    std::vector<double> knots;
    std::vector<Eigen::Vector4d> cntrl;
    std::vector<Eigen::Vector3d> scratch;
  };
  NurbsInput nurbs_;

  struct Ending {
    bool fini_seen = false;    // FINI
    bool end_of_path = false;  // the last statement was END-OF-PATH
    bool input_done = false;
  };
  Ending end_;
};

}  // namespace vcpost::cldata
