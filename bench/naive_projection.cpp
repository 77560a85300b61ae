// The naive reference of bench/scale.sh: closest points on a STEP model the
// way one first writes them with OpenCASCADE, every query point projected
// onto every face with GeomAPI_ProjectPointOnSurf (one projector per face,
// set up once on the face's natural (u,v) bounds; no spatial index, no warm
// start, no trim check) and the nearest answer kept.
//
//   naive_projection MODEL.step PROGRAM.nc [--sample M] [--ball-radius R]
//                    [--max-seconds S]
//
// The query points are the end points of every k-th feed move of the
// G-code program (k chosen so that about M, default 2000, are taken, spread
// over the whole program), moved up by R (default 0) along z: with R the
// ball radius and tip CL points, the ball centres that vcpost post queries.
// Projection stops early after S seconds (default 60; the points done are
// counted). Only the projections are timed, wall clock and process CPU
// time (one thread: CPU time is what a loaded machine does not inflate).
//
// Output: one line "naive_projection: points N faces F seconds T
// points_per_s P cpu_seconds C points_per_cpu_s Q mean_distance D
// max_distance_dev E" (D the mean distance
// found, E the largest |distance - R|: a sanity check that the nearest
// surface point was found, about 0 for a ball program's centres). Exit
// codes: 0 done, 2 bad usage or input.
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_Surface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "postproc/gcode/diagnostics.h"
#include "postproc/gcode/interpreter.h"

namespace {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A read-only memory map of a whole file (the interpreter reads a view).
class MappedFile {
 public:
  explicit MappedFile(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY);
    if (fd < 0) throw UsageError(path + ": cannot open");
    struct stat st {};
    if (::fstat(fd, &st) != 0 || st.st_size == 0) {
      ::close(fd);
      throw UsageError(path + ": empty or unreadable");
    }
    size_ = static_cast<std::size_t>(st.st_size);
    data_ = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
    ::close(fd);
    if (data_ == MAP_FAILED) throw UsageError(path + ": cannot map");
  }
  ~MappedFile() { ::munmap(data_, size_); }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  std::string_view text() const { return {static_cast<const char*>(data_), size_}; }

 private:
  void* data_ = nullptr;
  std::size_t size_ = 0;
};

// Calls f(end point) for every feed move of the program, in order.
template <typename F>
void for_each_feed_end(std::string_view text, F&& f) {
  using namespace vcpost;
  gcode::Interpreter in(text, gcode::rs274ngc_dialect());
  std::vector<program::Event> events;
  while (true) {
    events.clear();
    if (!in.next(events)) break;
    for (const auto& e : events) {
      if (const auto* s = std::get_if<program::StraightFeed>(&e)) f(s->end);
      if (const auto* a = std::get_if<program::ArcFeed>(&e)) f(a->end);
    }
  }
}

struct Face {
  Handle(Geom_Surface) surface;
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
};

std::vector<Face> read_faces(const std::string& path) {
  STEPControl_Reader reader;
  if (reader.ReadFile(path.c_str()) != IFSelect_RetDone)
    throw UsageError(path + ": not a STEP file");
  reader.TransferRoots();
  const TopoDS_Shape shape = reader.OneShape();
  std::vector<Face> faces;
  for (TopExp_Explorer x(shape, TopAbs_FACE); x.More(); x.Next()) {
    const TopoDS_Face& face = TopoDS::Face(x.Current());
    Face f;
    f.surface = BRep_Tool::Surface(face);  // with the face's location applied
    BRepTools::UVBounds(face, f.u0, f.u1, f.v0, f.v1);
    if (!f.surface.IsNull()) faces.push_back(f);
  }
  if (faces.empty()) throw UsageError(path + ": no faces");
  return faces;
}

double number(const char* option, const char* text) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(v) || v < 0) {
    throw UsageError(std::string(option) + ": a number >= 0 expected, got '" + text + "'");
  }
  return v;
}

int run(int argc, char** argv) {
  std::vector<std::string> files;
  double sample = 2000, radius = 0, max_seconds = 60;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--sample" || a == "--ball-radius" || a == "--max-seconds") && i + 1 < argc) {
      const double v = number(argv[i], argv[i + 1]);
      (a == "--sample" ? sample : a == "--ball-radius" ? radius : max_seconds) = v;
      ++i;
    } else if (a.starts_with("--")) {
      throw UsageError("unknown option " + a);
    } else {
      files.push_back(a);
    }
  }
  if (files.size() != 2 || sample < 1) {
    throw UsageError(
        "usage: naive_projection MODEL.step PROGRAM.nc [--sample M] [--ball-radius R] "
        "[--max-seconds S]");
  }
  const std::vector<Face> faces = read_faces(files[0]);

  // Two passes over the program: count the feed moves, then take every k-th.
  const MappedFile program(files[1]);
  std::uint64_t moves = 0;
  for_each_feed_end(program.text(), [&](const Eigen::Vector3d&) { ++moves; });
  if (moves == 0) throw UsageError(files[1] + ": no feed moves");
  const auto wanted = static_cast<std::uint64_t>(sample);
  const std::uint64_t k = std::max<std::uint64_t>(1, moves / wanted);
  std::vector<gp_Pnt> points;
  std::uint64_t index = 0;
  for_each_feed_end(program.text(), [&](const Eigen::Vector3d& p) {
    if (index++ % k == 0 && points.size() < wanted)
      points.emplace_back(p.x(), p.y(), p.z() + radius);
  });

  std::vector<GeomAPI_ProjectPointOnSurf> projectors(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    projectors[f].Init(faces[f].surface, faces[f].u0, faces[f].u1, faces[f].v0, faces[f].v1);
  }
  double sum = 0, worst_dev = 0;
  std::size_t done = 0;
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  double seconds = 0;
  for (const gp_Pnt& p : points) {
    double best = std::numeric_limits<double>::infinity();
    for (auto& projector : projectors) {
      projector.Perform(p);
      if (projector.NbPoints() > 0) best = std::min(best, projector.LowerDistance());
    }
    sum += best;
    worst_dev = std::max(worst_dev, std::abs(best - radius));
    ++done;
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (seconds > max_seconds) break;
  }
  const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  const auto n = static_cast<double>(done);
  std::printf(
      "naive_projection: points %zu faces %zu seconds %.3f points_per_s %.1f cpu_seconds %.3f "
      "points_per_cpu_s %.1f mean_distance %.6f max_distance_dev %.3g\n",
      done, faces.size(), seconds, n / seconds, cpu, n / cpu, sum / n, worst_dev);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "naive_projection: error: %s\n", e.what());
    return 2;
  } catch (const vcpost::gcode::GcodeError& e) {
    std::fprintf(stderr, "naive_projection: %s\n", e.what());
    return 2;
  } catch (const Standard_Failure& e) {
    std::fprintf(stderr, "naive_projection: OpenCASCADE failed: %s\n", e.GetMessageString());
    return 2;
  }
}
