// The sample parts: each surface with its default toolpath windows, and
// the programs committed in samples/ (the `samples` preset list).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "postproc/samplegen/surfaces.h"
#include "postproc/samplegen/toolpath.h"

namespace vcpost::samplegen {

struct Part {
  std::string name;  // "wavy", "patches", "cylinder", "dome"
  std::unique_ptr<SampleSurface> surface;
  // The STEP model is the surface cut into step_faces_u x step_faces_v
  // faces at equal steps of (u,v) (1 x 1: one face). The surface, hence the
  // truth, is the same whatever the cut.
  int step_faces_u = 1, step_faces_v = 1;
  double tool_diameter = 12;  // mm, the part's default ball
  double safe_z = 50;         // mm, tip height of the approach and retract: above the part
  // Defaults of the windows (see PathSpec): the ball-centre xy box (and
  // disc) of the raster, the (u,v) box of the iso-parametric patterns.
  Eigen::AlignedBox2d raster_window;
  std::optional<double> raster_radius;
  Eigen::AlignedBox2d iso_window;
};

// "wavy" | "patches" | "cylinder" | "dome"; empty for another name.
// "patches" is the wavy mould with its STEP model cut into 10 x 10 faces
// (the multi-face model of the scale benchmark; not in samples/).
std::optional<Part> make_part(const std::string& name);
// The parts of samples/ (without "patches").
std::vector<std::string> part_names();

// The chord tolerance of the programs of samples/, mm: half of vcpost's
// default contact tolerance (0.01), so they post without a gouge or a lift.
inline constexpr double kSampleChordTolerance = 0.005;

// One program of samples/: which part, the path, the file stem.
struct SampleProgram {
  std::string part;
  std::string stem;  // e.g. "cylinder_r100_ae0.5_a45"
  std::string title;
  PathSpec path;
  ProgramSpec program;
};

// The programs committed in samples/, in README order.
std::vector<SampleProgram> sample_programs();

}  // namespace vcpost::samplegen
