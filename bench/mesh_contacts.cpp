// The mesh index's answers, written out so that two builds can be compared
// query by query (a change to how the index is built must not change them).
//
//   mesh_contacts STL OUT [--queries N]   writes OUT
//   mesh_contacts --compare A B           compares two such files
//
// Queries (N of each kind, default 1,000,000; a fixed seed): cold points
// spread over the model's box grown by 3 mm; a warm raster path over the
// box at varying height, each query hinted by the previous answer; and
// points on the surface or just off it (0, 1e-6 and 0.01 mm along the
// normal of a cold answer), where several triangles meet and tie.
//
// --compare counts the queries whose point, normal, distance or type differ
// (bit for bit) and those whose face or uv differ; a face may differ only at
// a tie (the SurfaceModel contract: "ties: any of them"), so those are
// counted apart: same point, normal and distance, another face. Exit codes:
// 0 written or no point, normal, distance or type differs; 1 some differ;
// 2 bad usage or a file that cannot be read or written.
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "bench/record_file.h"
#include "geometry/mesh/mesh_model.h"
#include "geometry/mesh/stl_reader.h"

namespace {

using namespace vcpost;

// One answer as written: plain doubles and ints, no padding surprises.
struct Record {
  double point[3];
  double normal[3];
  double distance;
  double uv[2];
  std::int32_t face;
  std::int32_t type;  // ContactType, -1: no answer
};

Record record(const std::optional<geometry::ModelContact>& c) {
  Record r{};
  r.type = -1;
  if (!c) return r;
  for (int k = 0; k < 3; ++k) {
    r.point[k] = c->point[k];
    r.normal[k] = c->normal[k];
  }
  r.distance = c->distance;
  r.uv[0] = c->uv[0];
  r.uv[1] = c->uv[1];
  r.face = c->face;
  r.type = static_cast<std::int32_t>(c->type);
  return r;
}

int write(const std::string& stl, const std::string& out, std::size_t n) {
  const mesh::MeshModel model(mesh::read_stl_file(stl));
  const Eigen::AlignedBox3d box = model.bounds();
  const Eigen::Vector3d lo = box.min().array() - 3, hi = box.max().array() + 3;
  constexpr double far = std::numeric_limits<double>::infinity();
  std::mt19937_64 random(21);  // NOLINT(cert-msc32-c,cert-msc51-cpp): the same queries each run
  std::uniform_real_distribution<double> unit(0, 1);
  const auto spread = [&] {
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k) p[k] = lo[k] + (hi[k] - lo[k]) * unit(random);
    return p;
  };
  std::vector<Record> records;
  records.reserve(3 * n);
  // Cold, spread over the box.
  std::vector<geometry::ModelContact> cold;
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = model.closest_point(spread(), far, nullptr);
    records.push_back(record(c));
    if (c) cold.push_back(*c);
  }
  // Warm, along a raster at varying height.
  geometry::ContactHint hint;
  const auto rows = static_cast<std::size_t>(std::sqrt(static_cast<double>(n)));
  const std::size_t per_row = n / std::max<std::size_t>(rows, 1);
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t j = 0; j < per_row; ++j) {
      const double u = static_cast<double>(j) / static_cast<double>(per_row);
      const double v = (static_cast<double>(r) + 0.5) / static_cast<double>(rows);
      const Eigen::Vector3d p(lo.x() + (hi.x() - lo.x()) * (r % 2 == 0 ? u : 1 - u),
                              lo.y() + (hi.y() - lo.y()) * v,
                              lo.z() + (hi.z() - lo.z()) * (0.5 + 0.5 * std::sin(40 * u + 7 * v)));
      records.push_back(record(model.closest_point(p, far, &hint)));
    }
  }
  // On the surface and just off it, at the cold answers.
  const double offsets[3] = {0, 1e-6, 0.01};
  for (std::size_t i = 0; i < n && !cold.empty(); ++i) {
    const geometry::ModelContact& c = cold[i % cold.size()];
    const Eigen::Vector3d p = c.point + offsets[i % 3] * c.normal;
    records.push_back(record(model.closest_point(p, far, nullptr)));
  }
  const bool written = bench::write_records(out, records);
  std::printf("mesh_contacts: %zu answers written to %s\n", records.size(), out.c_str());
  return written ? 0 : 2;
}

int compare(const std::string& a_name, const std::string& b_name) {
  const std::vector<Record> a = bench::read_records<Record>(a_name),
                            b = bench::read_records<Record>(b_name);
  if (a.size() != b.size()) {
    std::printf("mesh_contacts: %zu answers against %zu\n", a.size(), b.size());
    return 1;
  }
  // Bit for bit (+0 and -0 differ, as two builds' answers must not).
  const auto same = [](const auto& x, const auto& y) {
    for (std::size_t k = 0; k < std::size(x); ++k)
      if (std::bit_cast<std::uint64_t>(x[k]) != std::bit_cast<std::uint64_t>(y[k])) return false;
    return true;
  };
  std::size_t contact = 0, tie = 0, uv = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Record& x = a[i];
    const Record& y = b[i];
    if (!same(x.point, y.point) || !same(x.normal, y.normal) ||
        !same(std::array{x.distance}, std::array{y.distance}) || x.type != y.type) {
      if (contact++ < 5)
        std::printf("differs at %zu: distance %.17g / %.17g, face %d / %d, type %d / %d\n", i,
                    x.distance, y.distance, x.face, y.face, x.type, y.type);
    } else if (x.face != y.face) {
      ++tie;
    } else if (!same(x.uv, y.uv)) {
      ++uv;
    }
  }
  std::printf(
      "mesh_contacts: %zu answers; point, normal, distance or type differ: %zu; the same "
      "contact on another face (a tie): %zu; the same face, other uv: %zu\n",
      a.size(), contact, tie, uv);
  return contact == 0 && uv == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc == 4 && std::string(argv[1]) == "--compare") return compare(argv[2], argv[3]);
    if (argc == 3) return write(argv[1], argv[2], 1'000'000);
    if (argc == 5 && std::string(argv[3]) == "--queries")
      return write(argv[1], argv[2], std::strtoull(argv[4], nullptr, 10));
    std::fprintf(stderr,
                 "usage: mesh_contacts STL OUT [--queries N] | mesh_contacts --compare A B\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mesh_contacts: %s\n", e.what());
    return 2;
  }
}
