// Where the in-process stock starts from (issue 44): the program's own
// declaration (Klartext BLK FORM, APT CL INSERT/Stock Size), a box the
// user gives, or a stock mesh. Pure text and values; the command line
// reads the files.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vcpost::post {

// The stock the program declares, mm, in the program's frame.
struct DeclaredStock {
  Eigen::AlignedBox3d box;
  std::string where;  // "file:line" of the declaration, for the summary
  std::string words;  // "BLK FORM" or "INSERT/Stock Size"
};

// The stock an APT CL program declares: INSERT/Stock Size X.. Y.. Z.., the
// sizes of a block whose corner lies at the origin and whose top is Z0
// (X 0..sx, Y 0..sy, Z -sz..0: the frame the shared CAM programs use);
// empty when it declares none. Throws vcpost::Error E4722 for an
// INSERT/Stock Size without three positive sizes.
std::optional<DeclaredStock> cl_declared_stock(std::string_view text, const std::string& file_name);

// A Klartext BLK FORM 0.1/0.2 as read by its interpreter (min, max, mm;
// `where` its 0.1 block). Throws vcpost::Error E4721 for a box with no
// volume (a 0.1 without its 0.2, or a max not above the min).
DeclaredStock klartext_declared_stock(const Eigen::Vector3d& min, const Eigen::Vector3d& max,
                                      const std::string& where);

// Where the stock of a job comes from; at most one of them.
struct StockSettings {
  bool from_program = false;               // the program's declaration (--stock-from-program)
  std::optional<Eigen::AlignedBox3d> box;  // --stock-box
  // --stock-model: triangles as corner triples, in the program's frame.
  std::shared_ptr<const std::vector<Eigen::Vector3f>> triangles;
  std::string model_name;         // its file, for the summary
  std::optional<double> cell_mm;  // --stock-cell; default from the posted tools
  std::size_t memory_limit = std::size_t{1024} << 20;  // --stock-memory, bytes
};

// --stock-box XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX. Throws vcpost::Error E4723
// for anything but six numbers with each min below its max.
Eigen::AlignedBox3d parse_stock_box(std::string_view text);

}  // namespace vcpost::post
