// STEP loading: file checks with our own messages first (OCCT's reader only
// says "fail"), then OCCT's reader with lengths converted to mm.
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <StepData_StepModel.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TopoDS_Shape.hxx>
#include <fstream>
#include <mutex>
#include <system_error>

#include "geometry/occt/brep_model.h"
#include "geometry/occt/shape_model.h"

namespace vcpost::occt {
namespace {

// OCCT's XSTEP settings are process-wide statics: loads take turns.
std::mutex& reader_mutex() {
  static std::mutex mutex;
  return mutex;
}

void check_file(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) {
    throw ModelError(ModelErrorCode::file_missing, name, "no such file");
  }
  if (std::filesystem::is_directory(status)) {
    throw ModelError(ModelErrorCode::file_unreadable, name, "is a directory, not a STEP file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in.is_open()) {
    throw ModelError(ModelErrorCode::file_unreadable, name,
                     "cannot be opened for reading (check its permissions)");
  }
  if (std::filesystem::file_size(path, error) == 0 && !error) {
    throw ModelError(ModelErrorCode::file_empty, name, "the file is empty");
  }
  std::string head(64, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (head.rfind("\xEF\xBB\xBF", 0) == 0) head.erase(0, 3);  // UTF-8 byte-order mark
  head.erase(0, head.find_first_not_of(" \t\r\n"));
  if (head.rfind("ISO-10303-21", 0) != 0) {
    throw ModelError(ModelErrorCode::not_step, name,
                     "not a STEP file: it does not start with 'ISO-10303-21;' "
                     "(STEP part 21 files do; STL models are read as meshes)");
  }
}

}  // namespace

BrepModel BrepModel::load_step(const std::filesystem::path& path, const BrepOptions& options) {
  check_file(path);
  const std::string name = path.string();
  TopoDS_Shape shape;
  std::string unit;
  try {
    const std::lock_guard<std::mutex> lock(reader_mutex());
    // Lengths come out of the transfer in this unit, whatever the file says.
    Interface_Static::SetCVal("xstep.cascade.unit", "MM");
    STEPControl_Reader reader;
    if (reader.ReadFile(name.c_str()) != IFSelect_RetDone) {
      throw ModelError(ModelErrorCode::not_step, name,
                       "the STEP reader refused the file (syntax errors or an unsupported "
                       "schema; AP203, AP214 and AP242 are read)");
    }
    // OCCT 7.6 scales to the model's local length unit (mm per unit).
    reader.StepModel()->SetLocalLengthUnit(1.0);
    TColStd_SequenceOfAsciiString lengths, angles, solid_angles;
    reader.FileUnits(lengths, angles, solid_angles);
    if (lengths.Length() > 0) unit = lengths.First().ToCString();
    const int roots = reader.NbRootsForTransfer();
    if (reader.TransferRoots() == 0) {
      throw ModelError(ModelErrorCode::no_faces, name,
                       roots == 0
                           ? std::string("the STEP file holds no shape entity (no solid, "
                                         "shell or face) to transfer")
                           : "OpenCASCADE transferred none of the file's " + std::to_string(roots) +
                                 " root entities to a shape (unresolved references or "
                                 "an unsupported representation); re-export the part "
                                 "as AP214 or AP242 B-rep");
    }
    shape = reader.OneShape();
  } catch (const Standard_Failure& failure) {
    throw ModelError(
        ModelErrorCode::kernel_failure, name,
        std::string("OpenCASCADE failed while reading: ") + failure.GetMessageString());
  }
  if (shape.IsNull()) {
    throw ModelError(ModelErrorCode::no_faces, name, "the STEP file holds no shape");
  }
  return model_from_shape(shape, options, name, unit);
}

}  // namespace vcpost::occt
