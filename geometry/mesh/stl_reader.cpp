#include "geometry/mesh/stl_reader.h"

#include <fcntl.h>
#include <oneapi/tbb/parallel_invoke.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <exception>

namespace vcpost::mesh {
namespace {

// Welds exactly equal corners (== on the coordinates: -0 and +0 weld);
// drops degenerate triangles. Vertices are numbered in the order they first
// appear. The index is an open-addressing table of vertex numbers probed
// linearly: 4 bytes a slot, no node per vertex (a 10 M-triangle file has
// some 5 M vertices; a node-based map cost 300 MB and most of the parse).
class MeshBuilder {
 public:
  MeshBuilder(StlMesh& mesh, std::size_t expected_vertices) : mesh_(mesh) {
    std::size_t size = 1024;
    while (size < 2 * expected_vertices) size *= 2;
    table_.assign(size, kEmpty);
  }

  void add(const std::array<Eigen::Vector3d, 3>& p) {
    add(p, {hash(p[0]), hash(p[1]), hash(p[2])});
  }

  // As add(p), with the corners' hashes already taken (hash(p[i])).
  void add(const std::array<Eigen::Vector3d, 3>& p, const std::array<std::size_t, 3>& hashes) {
    const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    if (!(n.squaredNorm() > 0.0)) {
      ++mesh_.degenerate_dropped;
      return;
    }
    std::array<std::uint32_t, 3> t{};
    for (int i = 0; i < 3; ++i) t[i] = index_of(p[i], hashes[i]);
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++mesh_.degenerate_dropped;
      return;
    }
    mesh_.triangles.push_back(t);
  }

  // Hints for a corner to be added soon: the table slot its hash starts
  // at, then the vertex found there. The welding is a chain of cache
  // misses (a slot, then the vertex it names) far apart in a table of
  // tens of MB; fetched ahead, they overlap. Hints only: nothing changes.
  void prefetch_slot(std::size_t h) const {
    __builtin_prefetch(table_.data() + (h & (table_.size() - 1)));
  }
  void prefetch_vertex(std::size_t h) const {
    const std::uint32_t v = table_[h & (table_.size() - 1)];
    if (v != kEmpty) __builtin_prefetch(mesh_.vertices.data() + v);
  }

  static std::size_t hash(const Eigen::Vector3d& p) {
    // +0.0 and -0.0 compare equal, so hash them alike.
    auto bits = [](double d) { return std::bit_cast<std::uint64_t>(d == 0.0 ? 0.0 : d); };
    std::uint64_t h = bits(p.x()) * 0x9E3779B97F4A7C15ULL;
    h ^= bits(p.y()) + 0x7F4A7C159E3779B9ULL + (h << 6) + (h >> 2);
    h ^= bits(p.z()) + 0x94D049BB133111EBULL + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h ^ (h >> 29));
  }

  // The number of the vertex at p (h = hash(p)), added when new.
  std::uint32_t index_of(const Eigen::Vector3d& p, std::size_t h) {
    const std::size_t mask = table_.size() - 1;
    for (std::size_t i = h & mask;; i = (i + 1) & mask) {
      const std::uint32_t v = table_[i];
      if (v == kEmpty) {
        const auto index = static_cast<std::uint32_t>(mesh_.vertices.size());
        table_[i] = index;
        mesh_.vertices.push_back(p);
        if (2 * mesh_.vertices.size() > table_.size()) grow();
        return index;
      }
      if (mesh_.vertices[v] == p) return v;
    }
  }

 private:
  static constexpr std::uint32_t kEmpty = 0xffffffffu;

  // Doubles the table (at most half full) and puts every vertex back.
  void grow() {
    table_.assign(2 * table_.size(), kEmpty);
    const std::size_t mask = table_.size() - 1;
    for (std::size_t v = 0; v < mesh_.vertices.size(); ++v) {
      std::size_t i = hash(mesh_.vertices[v]) & mask;
      while (table_[i] != kEmpty) i = (i + 1) & mask;
      table_[i] = static_cast<std::uint32_t>(v);
    }
  }

  StlMesh& mesh_;
  std::vector<std::uint32_t> table_;
};

float read_float(const char* p) {
  std::uint32_t u = 0;
  std::memcpy(&u, p, 4);
  if constexpr (std::endian::native == std::endian::big) u = __builtin_bswap32(u);
  return std::bit_cast<float>(u);
}

std::uint32_t read_u32(const char* p) {
  std::uint32_t u = 0;
  std::memcpy(&u, p, 4);
  if constexpr (std::endian::native == std::endian::big) u = __builtin_bswap32(u);
  return u;
}

// Binary STLs of at least this many triangles are welded in two halves.
constexpr std::uint64_t parallel_weld = std::uint64_t{1} << 20;

// Adds triangles [first, last) of a binary STL to builder's mesh.
void weld_binary(std::string_view bytes, const std::string& file, double unit, std::uint64_t first,
                 std::uint64_t last, MeshBuilder& builder) {
  // The corners' hashes are taken `ahead` triangles early and their table
  // slots fetched, then half way there the vertices those slots name
  // (10 M triangles: 2.1 s of CPU without, 0.95 s with).
  constexpr std::uint64_t ahead = 16;
  std::array<std::size_t, 3> hashes[2 * ahead];
  const auto hash_ahead = [&](std::uint64_t u) {
    const char* rec = bytes.data() + 84 + 50 * u;
    for (int c = 0; c < 3; ++c) {
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k)
        p[k] = static_cast<double>(read_float(rec + 12 + 12 * c + 4 * k)) * unit;
      hashes[u % (2 * ahead)][c] = MeshBuilder::hash(p);
      builder.prefetch_slot(hashes[u % (2 * ahead)][c]);
    }
  };
  for (std::uint64_t u = first; u < std::min(last, first + ahead); ++u) hash_ahead(u);
  for (std::uint64_t t = first; t < last; ++t) {
    if (t + ahead < last) hash_ahead(t + ahead);
    if (t + ahead / 2 < last)
      for (const std::size_t h : hashes[(t + ahead / 2) % (2 * ahead)]) builder.prefetch_vertex(h);
    const char* rec = bytes.data() + 84 + 50 * t;
    std::array<Eigen::Vector3d, 3> p;
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 3; ++k) {
        const float f = read_float(rec + 12 + 12 * c + 4 * k);
        if (!std::isfinite(f)) {
          const std::uint64_t off = 84 + 50 * t + 12 + 12 * static_cast<std::uint64_t>(c) +
                                    4 * static_cast<std::uint64_t>(k);
          throw StlError(Code::E4605, file, off,
                         "triangle " + std::to_string(t + 1) + " vertex " + std::to_string(c + 1) +
                             " has a non-finite coordinate (" + std::to_string(f) + ")");
        }
        p[c][k] = static_cast<double>(f) * unit;
      }
    }
    builder.add(p, hashes[t % (2 * ahead)]);
  }
}

StlMesh parse_binary(std::string_view bytes, const std::string& file, double unit) {
  StlMesh mesh;
  mesh.format = StlFormat::binary;
  if (bytes.size() < 84) {
    throw StlError(Code::E4604, file, bytes.size(),
                   "binary STL shorter than its 84-byte header (" + std::to_string(bytes.size()) +
                       " bytes), and not ASCII STL either");
  }
  std::string header(bytes.substr(0, 80));
  header = header.substr(0, header.find('\0'));
  while (!header.empty() && std::isspace(static_cast<unsigned char>(header.back())))
    header.pop_back();
  mesh.solid_name = header;
  const std::uint64_t count = read_u32(bytes.data() + 80);
  const std::uint64_t need = 84 + 50 * count;
  if (bytes.size() < need) {
    const std::uint64_t complete = (bytes.size() - 84) / 50;
    throw StlError(Code::E4604, file, 84 + 50 * complete,
                   "binary STL truncated: header announces " + std::to_string(count) +
                       " triangles (" + std::to_string(need) + " bytes) but the file has " +
                       std::to_string(bytes.size()) + " bytes (" + std::to_string(complete) +
                       " complete triangles)");
  }
  mesh.trailing_bytes = bytes.size() - need;
  if (mesh.trailing_bytes >= 50) {
    // More whole triangles than the count says: reading up to the count
    // would silently drop part of the model.
    throw StlError(Code::E4609, file, need,
                   "binary STL header announces " + std::to_string(count) +
                       " triangles but the file holds " + std::to_string((bytes.size() - 84) / 50) +
                       " whole triangle records; the count is wrong (a damaged or concatenated "
                       "file): export the model again");
  }
  mesh.triangles.reserve(count);
  mesh.vertices.reserve(count / 2 + 3);
  MeshBuilder builder(mesh, count / 2 + 3);
  if (count < parallel_weld) {
    weld_binary(bytes, file, unit, 0, count, builder);
  } else {
    // The halves welded side by side, then the second's vertices put
    // through the first's table in their order: those it has keep its
    // numbers, the others follow. Numbers, triangles and errors as one pass
    // in file order gives (10 M triangles: 0.98 -> 0.74 s on two free cores).
    const std::uint64_t half = count / 2;
    StlMesh second;
    second.triangles.reserve(count - half);
    second.vertices.reserve(half / 2 + 3);
    MeshBuilder second_builder(second, half / 2 + 3);
    std::exception_ptr error[2];
    tbb::parallel_invoke(
        [&] {
          try {
            weld_binary(bytes, file, unit, 0, half, builder);
          } catch (...) {
            error[0] = std::current_exception();
          }
        },
        [&] {
          try {
            weld_binary(bytes, file, unit, half, count, second_builder);
          } catch (...) {
            error[1] = std::current_exception();
          }
        });
    for (const auto& e : error)
      if (e) std::rethrow_exception(e);
    const std::vector<Eigen::Vector3d>& later = second.vertices;
    std::vector<std::uint32_t> number(later.size());
    constexpr std::size_t ahead = 16;
    std::size_t hashes[2 * ahead];
    for (std::size_t j = 0; j < std::min(later.size(), ahead); ++j) {
      hashes[j] = MeshBuilder::hash(later[j]);
      builder.prefetch_slot(hashes[j]);
    }
    for (std::size_t j = 0; j < later.size(); ++j) {
      if (j + ahead < later.size()) {
        hashes[(j + ahead) % (2 * ahead)] = MeshBuilder::hash(later[j + ahead]);
        builder.prefetch_slot(hashes[(j + ahead) % (2 * ahead)]);
      }
      if (j + ahead / 2 < later.size())
        builder.prefetch_vertex(hashes[(j + ahead / 2) % (2 * ahead)]);
      number[j] = builder.index_of(later[j], hashes[j % (2 * ahead)]);
    }
    for (const auto& t : second.triangles)
      mesh.triangles.push_back({number[t[0]], number[t[1]], number[t[2]]});
    mesh.degenerate_dropped += second.degenerate_dropped;
  }
  if (mesh.triangles.empty()) {
    throw StlError(Code::E4606, file, 80,
                   (count == 0 ? std::string("binary STL with zero triangles")
                               : "binary STL whose " + std::to_string(count) +
                                     " triangles are all degenerate"));
  }
  return mesh;
}

// Whitespace-separated words with their line and column.
class Words {
 public:
  Words(std::string_view text) : text_(text) {}

  struct Word {
    std::string_view text;
    std::uint32_t line = 0;
    std::uint32_t column = 0;
  };

  // The next word; empty text at the end.
  Word next() {
    skip_space();
    Word w{{}, line_, column()};
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    w.text = text_.substr(start, pos_ - start);
    return w;
  }

  // The rest of the current line (after the last word), trimmed.
  std::string rest_of_line() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    std::string s(text_.substr(start, pos_ - start));
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return {};
    s = s.substr(b);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
    return s;
  }

 private:
  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
      if (text_[pos_] == '\n') {
        ++line_;
        line_start_ = pos_ + 1;
      }
      ++pos_;
    }
  }
  std::uint32_t column() const { return static_cast<std::uint32_t>(pos_ - line_start_ + 1); }

  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_start_ = 0;
  std::uint32_t line_ = 1;
};

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) !=
        std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  }
  return true;
}

StlMesh parse_ascii(std::string_view bytes, const std::string& file, double unit) {
  StlMesh mesh;
  mesh.format = StlFormat::ascii;
  MeshBuilder builder(mesh, bytes.size() / 400);
  Words words(bytes);
  std::uint64_t facets = 0;

  auto word_text = [](const Words::Word& w) {
    return w.text.empty() ? std::string("the end of the file") : "'" + std::string(w.text) + "'";
  };
  auto expect = [&](std::string_view keyword, std::string_view context) {
    const Words::Word w = words.next();
    if (!iequals(w.text, keyword)) {
      const Code code = w.text.empty() ? Code::E4604 : Code::E4607;
      throw StlError(code, {file, w.line, w.column},
                     "expected '" + std::string(keyword) + "' " + std::string(context) +
                         ", found " + word_text(w));
    }
  };
  auto number = [&](bool must_be_finite, std::string_view what) {
    const Words::Word w = words.next();
    double v = 0.0;
    const char* b = w.text.data();
    const char* e = b + w.text.size();
    if (!w.text.empty() && *b == '+') ++b;  // from_chars refuses a leading '+'
    const auto [ptr, ec] = std::from_chars(b, e, v);
    if (w.text.empty()) {
      throw StlError(Code::E4604, {file, w.line, w.column},
                     "file ends inside a facet (expected " + std::string(what) + ")");
    }
    if (ec != std::errc() || ptr != e || (must_be_finite && !std::isfinite(v))) {
      throw StlError(Code::E4605, {file, w.line, w.column},
                     std::string(what) + " is not a finite number: '" + std::string(w.text) + "'");
    }
    return v;
  };

  bool any_solid = false;
  for (;;) {
    Words::Word w = words.next();
    if (w.text.empty()) {
      if (any_solid) break;
      throw StlError(Code::E4603, {file, w.line, w.column}, "STL file holds only white space");
    }
    if (!iequals(w.text, "solid")) {
      throw StlError(Code::E4607, {file, w.line, w.column},
                     "expected 'solid', found " + word_text(w));
    }
    any_solid = true;
    const std::string name = words.rest_of_line();
    if (mesh.solid_name.empty()) mesh.solid_name = name;
    for (;;) {
      w = words.next();
      if (iequals(w.text, "endsolid")) {
        words.rest_of_line();
        break;
      }
      if (!iequals(w.text, "facet")) {
        const Code code = w.text.empty() ? Code::E4604 : Code::E4607;
        throw StlError(code, {file, w.line, w.column},
                       "expected 'facet' or 'endsolid', found " + word_text(w));
      }
      expect("normal", "after 'facet'");
      // Exporters write nan normals for slivers; the normal is recomputed anyway.
      for (int k = 0; k < 3; ++k) number(false, "facet normal component");
      expect("outer", "after the facet normal");
      expect("loop", "after 'outer'");
      std::array<Eigen::Vector3d, 3> p;
      for (int c = 0; c < 3; ++c) {
        expect("vertex", "(a facet has three vertices)");
        for (int k = 0; k < 3; ++k) p[c][k] = number(true, "vertex coordinate") * unit;
      }
      expect("endloop", "after the third vertex");
      expect("endfacet", "after 'endloop'");
      builder.add(p);
      ++facets;
    }
  }
  if (mesh.triangles.empty()) {
    throw StlError(
        Code::E4606, {file, 1, 1},
        (facets == 0 ? std::string("ASCII STL with no facet")
                     : "ASCII STL whose " + std::to_string(facets) + " facets are all degenerate"));
  }
  return mesh;
}

bool starts_with_solid(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[i]))) ++i;
  return bytes.size() - i >= 5 && iequals(bytes.substr(i, 5), "solid") &&
         (bytes.size() - i == 5 || std::isspace(static_cast<unsigned char>(bytes[i + 5])));
}

std::string format_double(double v, int precision) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, precision);
  return std::string(buf, r.ptr);
}

}  // namespace

StlMesh parse_stl(std::string_view bytes, const std::string& file_name, const StlOptions& options) {
  if (!(options.unit_mm > 0.0) || !std::isfinite(options.unit_mm)) {
    throw StlError(
        Code::E4608, {file_name},
        "model unit must be a positive length in mm, got " + std::to_string(options.unit_mm));
  }
  if (bytes.empty()) {
    throw StlError(Code::E4603, file_name, 0, "STL file is empty (0 bytes)");
  }
  const bool blank = std::all_of(bytes.begin(), bytes.end(), [](char c) {
    return std::isspace(static_cast<unsigned char>(c));
  });
  if (blank) {
    throw StlError(Code::E4603, file_name, 0, "STL file holds only white space");
  }
  // Binary when the size matches the count exactly: the only reliable sign.
  if (bytes.size() >= 84) {
    const std::uint64_t count = read_u32(bytes.data() + 80);
    if (84 + 50 * count == bytes.size()) return parse_binary(bytes, file_name, options.unit_mm);
  }
  if (starts_with_solid(bytes) && bytes.find('\0') == std::string_view::npos) {
    return parse_ascii(bytes, file_name, options.unit_mm);
  }
  if (starts_with_solid(bytes) && bytes.size() < 84) {
    return parse_ascii(bytes, file_name, options.unit_mm);
  }
  // Text that is not ASCII STL would otherwise be blamed as a truncated binary.
  const bool text = std::none_of(bytes.begin(), bytes.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return u < 0x09 || (u > 0x0D && u < 0x20) || u == 0x7F;
  });
  if (text) {
    throw StlError(Code::E4607, {file_name, 1, 1},
                   "text file that is not ASCII STL (it does not start "
                   "with 'solid') nor binary STL");
  }
  return parse_binary(bytes, file_name, options.unit_mm);
}

StlMesh read_stl_file(const std::filesystem::path& path, const StlOptions& options) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) {
    throw StlError(Code::E4601, {path.string()}, "STL file not found");
  }
  if (std::filesystem::is_directory(status)) {
    throw StlError(Code::E4602, {path.string()}, "is a directory, not an STL file");
  }
  // The file is mapped, not copied: a 500 MB mesh would otherwise be read
  // through a growing buffer (twice its size at the peak) before parsing.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  struct stat info {};
  if (fd < 0 || ::fstat(fd, &info) != 0) {
    if (fd >= 0) ::close(fd);
    throw StlError(Code::E4602, {path.string()}, "cannot read the file (permissions?)");
  }
  const auto size = static_cast<std::size_t>(info.st_size);
  if (!S_ISREG(info.st_mode) || size == 0) {
    // Not mappable (a device, an empty file): read it as it comes.
    std::string bytes;
    char chunk[65536];
    ssize_t got = 0;
    while ((got = ::read(fd, chunk, sizeof chunk)) > 0)
      bytes.append(chunk, static_cast<std::size_t>(got));
    ::close(fd);
    if (got < 0) {
      throw StlError(Code::E4602, {path.string()}, "cannot read the file (permissions?)");
    }
    return parse_stl(bytes, path.string(), options);
  }
  void* const map = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
  ::close(fd);  // the mapping keeps the file
  if (map == MAP_FAILED) {
    throw StlError(Code::E4602, {path.string()}, "cannot read the file (permissions?)");
  }
  ::madvise(map, size, MADV_SEQUENTIAL);
  struct Unmap {
    void* map;
    std::size_t size;
    ~Unmap() { ::munmap(map, size); }
  } unmap{map, size};
  return parse_stl(std::string_view(static_cast<const char*>(map), size), path.string(), options);
}

std::string to_ascii_stl(const StlMesh& mesh, const std::string& name, int precision) {
  std::string out = "solid " + name + "\n";
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d& b = mesh.vertices[t[1]];
    const Eigen::Vector3d& c = mesh.vertices[t[2]];
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() > 0) n.normalize();
    out += "  facet normal " + format_double(n.x(), precision) + " " +
           format_double(n.y(), precision) + " " + format_double(n.z(), precision) +
           "\n    outer loop\n";
    for (const auto* p : {&a, &b, &c}) {
      out += "      vertex " + format_double(p->x(), precision) + " " +
             format_double(p->y(), precision) + " " + format_double(p->z(), precision) + "\n";
    }
    out += "    endloop\n  endfacet\n";
  }
  out += "endsolid " + name + "\n";
  return out;
}

std::string to_binary_stl(const StlMesh& mesh, const std::string& header) {
  std::string out(84 + 50 * mesh.triangles.size(), '\0');
  std::memcpy(out.data(), header.data(), std::min<std::size_t>(header.size(), 80));
  auto put_u32 = [&](std::size_t at, std::uint32_t u) {
    if constexpr (std::endian::native == std::endian::big) u = __builtin_bswap32(u);
    std::memcpy(out.data() + at, &u, 4);
  };
  auto put_float = [&](std::size_t at, double v) {
    put_u32(at, std::bit_cast<std::uint32_t>(static_cast<float>(v)));
  };
  put_u32(80, static_cast<std::uint32_t>(mesh.triangles.size()));
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    const std::size_t rec = 84 + 50 * i;
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    Eigen::Vector3d n = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
    if (n.norm() > 0) n.normalize();
    for (int k = 0; k < 3; ++k) put_float(rec + 4 * k, n[k]);
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) put_float(rec + 12 + 12 * c + 4 * k, mesh.vertices[t[c]][k]);
  }
  return out;
}

}  // namespace vcpost::mesh
