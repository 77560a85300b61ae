// Wall time and peak memory of loading a big binary STL (issue 21: 10 M
// triangles in under 5 s and 1.5 GB), through the loader `vcpost post
// --model` uses (cli::load_model: read, bounds check, index build).
//
//   mesh_load [FILE] [--triangles N] [--phases] [--keep]
//
// FILE (default /tmp/vcpost_mesh_load_N.stl) is written first when it does
// not exist: the sample wavy mould (postproc/samplegen) tessellated into
// about N triangles (default 10,000,000; a grid, so vertices are shared, as
// an exporter writes a fine mould surface), in a child process so that its
// memory does not count. It is removed afterwards unless --keep is given
// or it existed before. --phases times the STL read and the index build
// apart (read_stl_file, then MeshModel: what load_model does, without its
// bounds check).
//
// Output: one line "mesh_load: triangles T vertices V seconds S cpu_seconds
// C peak_rss_mb M" (S wall clock, C user + system of the whole process,
// M = getrusage's ru_maxrss: the peak of the process, file pages mapped
// included), preceded with --phases by one line per phase. Exit codes: 0
// done, 2 bad usage or a file that cannot be written or read.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "geometry/mesh/mesh_model.h"
#include "geometry/mesh/stl_reader.h"
#include "postproc/cli/model_loader.h"
#include "postproc/samplegen/parts.h"
#include "postproc/samplegen/surface_mesh.h"

namespace {

using namespace vcpost;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  const auto s = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return s(u.ru_utime) + s(u.ru_stime);
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // KiB on Linux
}

// Writes the mould's binary STL in a child process (the generator holds the
// double mesh and the file's bytes at once: ~0.8 GB at 10 M triangles).
bool write_mould(const std::string& file, std::uint64_t triangles) {
  const pid_t child = fork();
  if (child < 0) return false;
  if (child == 0) {
    try {
      const auto part = samplegen::make_part("wavy");
      const auto mesh = samplegen::triangulate(*part->surface, triangles);
      const std::string bytes = mesh::to_binary_stl(mesh, "vcpost mesh_load wavy mould");
      std::ofstream out(file, std::ios::binary);
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      _exit(out.good() ? 0 : 1);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mesh_load: %s\n", e.what());
      _exit(1);
    }
  }
  int status = 0;
  waitpid(child, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

void print_phase(const char* name, Clock::time_point start, double cpu_start) {
  std::printf("mesh_load: phase %s seconds %.3f cpu_seconds %.3f peak_rss_mb %.0f\n", name,
              seconds_since(start), cpu_seconds() - cpu_start, peak_rss_mb());
}

int run(int argc, char** argv) {
  std::string file;
  std::uint64_t triangles = 10'000'000;
  bool phases = false, keep = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--triangles" && i + 1 < argc) {
      triangles = std::strtoull(argv[++i], nullptr, 10);
    } else if (a == "--phases") {
      phases = true;
    } else if (a == "--keep") {
      keep = true;
    } else if (!a.empty() && a[0] != '-' && file.empty()) {
      file = a;
    } else {
      std::fprintf(stderr, "usage: mesh_load [FILE] [--triangles N] [--phases] [--keep]\n");
      return 2;
    }
  }
  if (triangles < 2) triangles = 2;
  if (file.empty()) file = "/tmp/vcpost_mesh_load_" + std::to_string(triangles) + ".stl";
  const bool existed = std::filesystem::exists(file);
  if (!existed && !write_mould(file, triangles)) {
    std::fprintf(stderr, "mesh_load: cannot write %s\n", file.c_str());
    return 2;
  }
  std::size_t faces = 0, vertices = 0;
  const auto start = Clock::now();
  const double cpu_start = cpu_seconds();
  if (phases) {
    mesh::StlMesh m = mesh::read_stl_file(file);
    print_phase("read", start, cpu_start);
    const auto build_start = Clock::now();
    const double build_cpu = cpu_seconds();
    vertices = m.vertices.size();
    const mesh::MeshModel model(std::move(m));
    faces = static_cast<std::size_t>(model.face_count());
    print_phase("index", build_start, build_cpu);
  } else {
    const cli::LoadedModel loaded = cli::load_model(file);
    faces = static_cast<std::size_t>(loaded.model->face_count());
    vertices = dynamic_cast<const mesh::MeshModel&>(*loaded.model).vertex_count();
  }
  std::printf(
      "mesh_load: triangles %zu vertices %zu seconds %.3f cpu_seconds %.3f peak_rss_mb %.0f\n",
      faces, vertices, seconds_since(start), cpu_seconds() - cpu_start, peak_rss_mb());
  if (!existed && !keep) std::filesystem::remove(file);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mesh_load: %s\n", e.what());
    return 2;
  }
}
