// The bull-nose and flat end mills' contacts (geometry/tool_contact.h) along
// a G-code program, as `vcpost post` asks for them: every G1 end point in
// order, one hint, the tip as the CL point. Prints the closest-point queries
// per point and the CPU time per contact, and writes the answers so that two
// builds can be compared contact by contact.
//
//   tool_contacts MODEL GCODE TOOL OUT   e.g. wavy.step bull200k.nc bull:10:2 a.bin
//   tool_contacts --compare A B          the largest differences between two such files
//
// The G-code reader is the generator's subset (vcpost-samplegen): absolute
// X, Y, Z words, G0 moves skipped. Exit codes: 0 written, or compared with
// no status differing; 1 some status differs; 2 bad usage or unreadable
// files.
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <exception>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/record_file.h"
#include "geometry/tool_contact.h"
#include "postproc/cli/model_loader.h"

namespace {

using namespace vcpost;
using Eigen::Vector3d;

// One answer as written: plain doubles and ints.
struct Record {
  double point[3];
  double normal[3];
  double distance_error;
  std::int32_t status;  // BallStatus
  std::int32_t face;
};

Record record(const geometry::BallContact& c) {
  Record r{};
  for (int k = 0; k < 3; ++k) {
    r.point[k] = c.contact ? c.contact->point[k] : 0.0;
    r.normal[k] = c.normal[k];
  }
  r.distance_error = c.distance_error;
  r.status = static_cast<std::int32_t>(c.status);
  r.face = c.contact ? c.contact->face : -1;
  return r;
}

// The CL points of the program's feed moves (modal X, Y, Z; G0 lines skipped).
std::vector<Vector3d> feed_points(const std::string& name) {
  std::ifstream file(name);
  if (!file) throw std::runtime_error("cannot read " + name);
  std::vector<Vector3d> points;
  Vector3d at = Vector3d::Zero();
  bool rapid = false;
  for (std::string line; std::getline(file, line);) {
    if (line.empty() || line[0] == '(' || line[0] == '%') continue;
    bool moved = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char word = line[i];
      if (word != 'G' && word != 'X' && word != 'Y' && word != 'Z') continue;
      std::size_t used = 0;
      const double value = std::stod(line.substr(i + 1), &used);
      i += used;
      if (word == 'G') {
        if (value == 0) rapid = true;
        if (value == 1) rapid = false;
      } else {
        at[word - 'X'] = value;
        moved = true;
      }
    }
    if (moved && !rapid) points.push_back(at);
  }
  return points;
}

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

int write(const std::string& model_name, const std::string& gcode, const std::string& tool_spec,
          const std::string& out) {
  const cli::LoadedModel loaded = cli::load_model(model_name);
  const geometry::Tool tool = geometry::parse_tool(tool_spec);
  const std::vector<Vector3d> points = feed_points(gcode);
  std::vector<Record> records;
  records.reserve(points.size());
  geometry::ContactHint hint;
  const double start = cpu_seconds();
  for (const Vector3d& p : points) {
    const Vector3d origin = geometry::tool_origin(p, tool, geometry::ClPoint::tip);
    records.push_back(
        record(geometry::tool_contact(*loaded.model, tool, origin, 0.01, tool.diameter, &hint)));
  }
  const double cpu = cpu_seconds() - start;
  const auto n = static_cast<double>(std::max<std::size_t>(points.size(), 1));
  std::printf(
      "tool_contacts: %zu points, %.3f queries a point (%.3f warm, %.3f cold), %.3f us CPU a "
      "contact\n",
      points.size(), static_cast<double>(hint.warm_queries + hint.cold_queries) / n,
      static_cast<double>(hint.warm_queries) / n, static_cast<double>(hint.cold_queries) / n,
      1e6 * cpu / n);
  const bool written = bench::write_records(out, records);
  return written ? 0 : 2;
}

double gap(const double (&a)[3], const double (&b)[3]) {
  const Vector3d d = Vector3d(a[0], a[1], a[2]) - Vector3d(b[0], b[1], b[2]);
  return d.norm();
}

int compare(const std::string& a_name, const std::string& b_name) {
  const std::vector<Record> a = bench::read_records<Record>(a_name),
                            b = bench::read_records<Record>(b_name);
  if (a.size() != b.size()) {
    std::printf("tool_contacts: %zu answers against %zu\n", a.size(), b.size());
    return 1;
  }
  std::size_t status = 0, face = 0, worst = 0;
  double point = 0, normal = 0, error = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].status != b[i].status) {
      if (status++ < 5) std::printf("status differs at %zu\n", i);
      continue;
    }
    if (a[i].face != b[i].face) ++face;
    const double moved = gap(a[i].point, b[i].point);
    if (moved > point) worst = i;
    point = std::max(point, moved);
    normal = std::max(normal, gap(a[i].normal, b[i].normal));
    error = std::max(error, std::abs(a[i].distance_error - b[i].distance_error));
  }
  std::printf(
      "tool_contacts: %zu answers; status differs: %zu, face differs: %zu; largest differences: "
      "contact point %.3g mm (at %zu), normal %.3g, distance error %.3g mm\n",
      a.size(), status, face, point, worst, normal, error);
  return status == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc == 4 && std::string(argv[1]) == "--compare") return compare(argv[2], argv[3]);
    if (argc == 5) return write(argv[1], argv[2], argv[3], argv[4]);
    std::fprintf(stderr,
                 "usage: tool_contacts MODEL GCODE TOOL OUT | tool_contacts --compare A B\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tool_contacts: %s\n", e.what());
    return 2;
  }
}
