// STEP loading: file checks with our own messages first (OCCT's reader only
// says "fail"), then OCCT's reader with lengths converted to mm.
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Check.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <StepBasic_SiUnitAndLengthUnit.hxx>
#include <StepData_StepModel.hxx>
#include <StepGeom_CartesianPoint.hxx>
#include <StepGeom_Direction.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TopoDS_Shape.hxx>
#include <cmath>
#include <fstream>
#include <mutex>
#include <system_error>
#include <vector>

#include "geometry/occt/brep_model.h"
#include "geometry/occt/quiet_messenger.h"
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
    throw ModelError(Code::E4101, name, "no such file");
  }
  if (std::filesystem::is_directory(status)) {
    throw ModelError(Code::E4102, name, "is a directory, not a STEP file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in.is_open()) {
    throw ModelError(Code::E4102, name, "cannot be opened for reading (check its permissions)");
  }
  if (std::filesystem::file_size(path, error) == 0 && !error) {
    throw ModelError(Code::E4103, name, "the file is empty");
  }
  std::string head(64, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (head.rfind("\xEF\xBB\xBF", 0) == 0) head.erase(0, 3);  // UTF-8 byte-order mark
  head.erase(0, head.find_first_not_of(" \t\r\n"));
  if (head.rfind("ISO-10303-21", 0) != 0) {
    throw ModelError(Code::E4104, name,
                     "not a STEP file: it does not start with 'ISO-10303-21;' "
                     "(STEP part 21 files do; STL models are read as meshes)");
  }
}

// What OpenCASCADE reads without complaint but then loads wrongly: an
// entity it could not parse or resolve (it drops it and transfers the rest:
// a face without its boundary becomes an infinite plane, and a malformed
// EDGE_LOOP has crashed the transfer), a number that is not finite (1.E400
// reads as infinity, and meshing it never ends), a length unit that is not
// a length (SI_UNIT(.MILLI.,.GRAM.) comes back as "milli", read as mm).
void check_entities(const StepData_StepModel& model, const std::string& name) {
  // Errors that lose entities refuse the file; an ident defined twice (OCCT
  // keeps the first; found in real exports) does not.
  const Handle(Interface_Check) global = model.GlobalCheck();
  std::vector<std::string> errors;
  for (int k = 1; k <= global->NbFails(); ++k) {
    std::string fail = global->CFail(k);
    if (fail.rfind("Ident defined SEVERAL TIMES", 0) == 0) continue;
    const std::string prefix = "Undefined Parsing: ";  // OCCT's words for a syntax error
    if (fail.rfind(prefix, 0) == 0) fail.erase(0, prefix.size());
    // OCCT counts the line where its scanner stood: the error's, or the next.
    if (fail.rfind("Line ", 0) == 0) fail.replace(0, 5, "near line ");
    errors.push_back(fail);
  }
  if (!errors.empty()) {
    const std::size_t more = errors.size() - 1;
    throw ModelError(Code::E4104, name,
                     "the STEP reader found errors (" + errors.front() +
                         (more > 0 ? "; and " + std::to_string(more) + " more" : "") +
                         "); OpenCASCADE would leave those entities out and load a different "
                         "shape: mend the file or export it again");
  }
  const auto label = [&](const Handle(Standard_Transient) & entity) {
    return "#" + std::to_string(model.IdentLabel(entity));
  };
  for (int i = 1; i <= model.NbEntities(); ++i) {
    const Handle(Standard_Transient)& entity = model.Value(i);
    if (const auto point = Handle(StepGeom_CartesianPoint)::DownCast(entity)) {
      for (int k = 1; k <= point->NbCoordinates(); ++k) {
        if (!std::isfinite(point->CoordinatesValue(k))) {
          throw ModelError(Code::E4107, name,
                           label(entity) +
                               " CARTESIAN_POINT has a coordinate that is not a "
                               "finite number (beyond about 1.8E308)");
        }
      }
    } else if (const auto direction = Handle(StepGeom_Direction)::DownCast(entity)) {
      for (int k = 1; k <= direction->NbDirectionRatios(); ++k) {
        if (!std::isfinite(direction->DirectionRatiosValue(k))) {
          throw ModelError(Code::E4107, name,
                           label(entity) + " DIRECTION has a ratio that is not a finite number");
        }
      }
    } else if (const auto unit = Handle(StepBasic_SiUnitAndLengthUnit)::DownCast(entity)) {
      if (unit->Name() != StepBasic_sunMetre) {
        throw ModelError(Code::E4107, name,
                         label(entity) +
                             " LENGTH_UNIT is an SI unit other than the metre: "
                             "lengths in this file cannot be read (export in mm "
                             "or inches)");
      }
    }
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
    const QuietMessenger quiet;  // the reader prints on stdout; errors get our own words
    // Lengths come out of the transfer in this unit, whatever the file says.
    Interface_Static::SetCVal("xstep.cascade.unit", "MM");
    STEPControl_Reader reader;
    if (reader.ReadFile(name.c_str()) != IFSelect_RetDone) {
      throw ModelError(Code::E4104, name,
                       "the STEP reader refused the file (syntax errors or an unsupported "
                       "schema; AP203, AP214 and AP242 are read)");
    }
    check_entities(*reader.StepModel(), name);
    // OCCT 7.6 scales to the model's local length unit (mm per unit).
    reader.StepModel()->SetLocalLengthUnit(1.0);
    TColStd_SequenceOfAsciiString lengths, angles, solid_angles;
    reader.FileUnits(lengths, angles, solid_angles);
    if (lengths.Length() > 0) unit = lengths.First().ToCString();
    const int roots = reader.NbRootsForTransfer();
    if (reader.TransferRoots() == 0) {
      throw ModelError(Code::E4105, name,
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
        Code::E4106, name,
        std::string("OpenCASCADE failed while reading: ") + failure.GetMessageString());
  }
  if (shape.IsNull()) {
    throw ModelError(Code::E4105, name, "the STEP file holds no shape");
  }
  return model_from_shape(shape, options, name, unit);
}

}  // namespace vcpost::occt
