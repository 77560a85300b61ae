#include "postproc/post/stock_source.h"

#include <array>
#include <sstream>

#include "core/error.h"
#include "core/text.h"

namespace vcpost::post {
namespace {

std::string shown(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out << v.x() << "," << v.y() << "," << v.z();
  return out.str();
}

}  // namespace

std::optional<DeclaredStock> cl_declared_stock(std::string_view text,
                                               const std::string& file_name) {
  std::size_t pos = 0;
  std::uint32_t line = 0;
  while (pos < text.size()) {
    std::size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) nl = text.size();
    const std::string_view raw = trim(text.substr(pos, nl - pos));
    pos = nl + 1;
    ++line;
    const std::string upper = to_upper(raw);
    if (!upper.starts_with("INSERT/STOCK SIZE")) continue;
    const std::string where = file_name + ":" + std::to_string(line);
    // X<sx> Y<sy> Z<sz>, each a number with an optional trailing point.
    std::array<std::optional<double>, 3> size;
    std::istringstream words(upper.substr(17));
    std::string word;
    while (words >> word) {
      const std::size_t axis = std::string_view("XYZ").find(word.front());
      if (axis == std::string_view::npos) continue;
      std::string_view digits = std::string_view(word).substr(1);
      if (digits.ends_with('.')) digits.remove_suffix(1);
      size[axis] = finite_number(digits);
    }
    for (const auto& s : size) {
      if (!s || !(*s > 0))
        throw vcpost::Error(Code::E4722,
                            where + ": '" + std::string(raw) +
                                "': the stock's X, Y and Z sizes, each above 0, expected");
    }
    DeclaredStock stock;
    stock.box = Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, -*size[2]),
                                    Eigen::Vector3d(*size[0], *size[1], 0));
    stock.where = where;
    stock.words = "INSERT/Stock Size";
    return stock;
  }
  return std::nullopt;
}

DeclaredStock klartext_declared_stock(const Eigen::Vector3d& min, const Eigen::Vector3d& max,
                                      const std::string& where) {
  if (!(max.array() > min.array()).all())
    throw vcpost::Error(Code::E4721, where + ": BLK FORM from " + shown(min) + " to " + shown(max) +
                                         " has no volume (a BLK FORM 0.1 without its 0.2?)");
  return {Eigen::AlignedBox3d(min, max), where, "BLK FORM"};
}

Eigen::AlignedBox3d parse_stock_box(std::string_view text) {
  std::array<double, 6> v{};
  std::size_t count = 0;
  std::size_t pos = 0;
  auto bad = [&](const std::string& why) {
    return vcpost::Error(Code::E4723, "--stock-box '" + std::string(text) + "': " + why);
  };
  while (pos <= text.size()) {
    std::size_t comma = text.find(',', pos);
    if (comma == std::string_view::npos) comma = text.size();
    const auto number = finite_number(trim(text.substr(pos, comma - pos)));
    if (!number) throw bad("six numbers XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX expected");
    if (count == v.size()) throw bad("more than six numbers");
    v[count++] = *number;
    pos = comma + 1;
  }
  if (count != v.size()) throw bad("six numbers XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX expected");
  const Eigen::Vector3d min(v[0], v[1], v[2]), max(v[3], v[4], v[5]);
  if (!(max.array() > min.array()).all()) throw bad("each max must be above its min");
  return {min, max};
}

}  // namespace vcpost::post
