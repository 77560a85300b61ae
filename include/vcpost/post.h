// The post job as a library call, what `vcpost post` does without the
// files: a finishing program's text in (G-code or APT CL data, recognised
// by content), the program with its spindle speeds S (and with adjust_feed
// its feeds F) rewritten so the real cutting speed stays at vc, within what
// the machine profile allows. G-code keeps every byte but the S/F words; CL
// data comes out as G-code in the profile's format.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vcpost/error.h"
#include "vcpost/export.h"
#include "vcpost/profile.h"
#include "vcpost/working_diameter.h"

namespace vcpost::geometry {
class SurfaceModel;
}

namespace vcpost::api {

// The finished surface the toolpath is posted against.
class VCPOST_API Model {
 public:
  // STEP (any length unit) or STL (mm), recognised by content. Throws Error
  // for a missing, unreadable or unusable file (E41xx for STEP).
  static Model load(const std::string& path);

  std::string kind() const;         // "STEP" or "STL"
  std::string description() const;  // e.g. "12 faces, unit MILLIMETRE"

  friend const geometry::SurfaceModel& internal(const Model& model);

 private:
  struct Loaded;
  explicit Model(std::shared_ptr<const Loaded> loaded);
  std::shared_ptr<const Loaded> loaded_;
};

// The reference diameter the speed is computed from: max (no engaged edge
// point faster than vc), tangent (the cutting point), mean (area mean).
enum class DiameterPolicy { max, tangent, mean };
// What the program's points are: the tool tip or the ball centre.
enum class ClPoint { tip, center };

// The options of `vcpost post`, with its defaults.
struct PostOptions {
  std::string tool;          // "ball:D"; empty: the CL program's first CUTTER
  double vc = 0;             // nominal cutting speed, m/min, > 0 (required)
  double ap = 0;             // depth of cut along the normal, mm, > 0 (required)
  std::optional<double> ae;  // width of cut where no neighbouring pass shows, mm
  bool ae_override = false;  // use `ae` everywhere instead of measuring it
  DiameterPolicy policy = DiameterPolicy::max;
  ClPoint cl_point = ClPoint::tip;
  double spacing_mm = 0.5;             // largest distance between evaluated points
  double contact_tolerance_mm = 0.01;  // distance error still counted as contact
  std::string dialect;                 // rs274ngc, fanuc or mazak; empty: the profile's
  bool adjust_feed = false;            // couple F = fz * z * n
  std::optional<double> fz_mm;         // feed per tooth; default: the program's F at its S
  std::optional<int> teeth;            // default: the profile's
  int threads = 0;                     // worker threads; 0: one per core (same output for any)
  bool keep_points = false;            // fill PostResult::points (memory grows with the program)
  // The in-process stock (docs/stock.md), at most one of the three: ap at
  // each point from the material the earlier sections left; none: `ap`.
  bool stock_from_program = false;                 // Klartext BLK FORM, APT CL INSERT/Stock Size
  std::optional<std::array<double, 6>> stock_box;  // xmin, ymin, zmin, xmax, ymax, zmax, mm
  std::string stock_model;                         // an STL of the raw part (mm), program frame
  std::optional<double> stock_cell_mm;             // default: the smallest tool's D/50 in [0.05, 1]
  double stock_memory_mb = 1024;                   // the field and its copies
};

// Cutting speed over the cutting points, weighted by cutting time, m/min.
struct VcStatistics {
  double min = 0, max = 0, mean = 0;
  double within_5_percent = 0;   // share of cutting time with |vc/vc_nominal - 1| <= 5 %
  double within_10_percent = 0;  // ... <= 10 %
};

// The in-process stock and the ap it gave (docs/stock.md, docs/json.md `stock`).
struct StockSummary {
  std::string source;  // e.g. "BLK FORM at part.h:19", "--stock-box"
  double cell_mm = 0;
  std::uint32_t nx = 0, ny = 0;
  std::uint64_t memory_bytes = 0;
  std::vector<std::string> warnings;  // sections left unswept (W4730, W4731)
  std::uint64_t points_stock = 0, points_clamped = 0, points_air = 0, points_given = 0;
  // Cutting time of the stock's points by ap / ap nominal: <= 1, <= 1.5, <= 2, > 2.
  std::array<double, 4> band_time_s{};
  std::uint64_t over_nominal_points = 0;  // ap above PostOptions::ap
  double over_nominal_time_s = 0, ap_max_mm = 0;
};

struct PostSummary {
  std::string kind;  // "gcode", "cldata" or "heidenhain"
  std::uint64_t blocks = 0, motion_events = 0, points = 0;
  std::uint64_t touching = 0, lifted = 0, gouging = 0, missed = 0;  // contact of the points
  std::uint64_t ae_measured = 0, ae_given = 0, ae_first_pass = 0;
  double program_time_s = 0, cutting_time_s = 0;
  std::uint64_t s_words = 0, f_words = 0;           // words written
  std::optional<VcStatistics> vc_before, vc_after;  // empty when no point cut
  std::optional<StockSummary> stock;                // with an in-process stock
};

// One evaluated point of the path (with keep_points).
struct PostPoint {
  std::uint32_t line = 0;            // NC line (CL record) of its block
  double time_s = 0;                 // from program start
  Vec3 point;                        // programmed point, mm
  bool touching = false;             // the ball touches the model there (within tolerance)
  std::optional<Vec3> contact;       // closest point on the model, mm
  Vec3 normal{0, 0, 1};              // the normal the tool sees
  std::optional<double> d_ref;       // the policy's working diameter, mm
  std::optional<double> ap;          // the depth of cut taken, mm (empty: not evaluated)
  bool ap_from_stock = false;        // from the in-process stock (0: nothing there to cut)
  double s_before = 0, s_after = 0;  // spindle speed in effect, rpm
};

struct PostResult {
  std::string program;  // the posted program
  PostSummary summary;
  std::vector<PostPoint> points;  // with keep_points, in path order
};

// Posts `program` (its whole text; `program_name` names it in messages).
// Throws Error for bad options or input (file:line:col and code as the
// command line prints them), and when the toolpath never touches the model.
VCPOST_API PostResult post(std::string_view program, const std::string& program_name,
                           const Model& model, const MachineProfile& profile,
                           const PostOptions& options);

}  // namespace vcpost::api
