// `vcpost deff`: the working-diameter model at one point, over a sweep of an
// angle, or for every row of a CSV file. Argument checks and printing only;
// the set-ups and numbers come from postproc/deff/.
#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/engagement.h"
#include "geometry/tool.h"
#include "postproc/cli/commands.h"
#include "postproc/cli/deff_output.h"
#include "postproc/cli/interrupt.h"
#include "postproc/deff/batch_reader.h"
#include "postproc/deff/evaluation.h"
#include "postproc/deff/setup_input.h"

namespace vcpost::cli {
namespace {

using namespace vcpost::deff;
using namespace deff_printing;

constexpr const char* kDeffDescription =
    "Working diameter of the tool at one point, over a sweep of an angle, or for every row of a\n"
    "CSV file (Mgherony-Miko model, MODELS.md section 2). Reports D_max, D_min, D_mean and the\n"
    "cutting points 1, 2, 1', 1'', 2', 2'' as 2r (r = distance from the tool axis), in mm.\n"
    "\n"
    "Examples:\n"
    "  the paper's case (D 10 mm, ap 0.3 mm, surface tilted 25 deg at azimuth 35 deg):\n"
    "    vcpost deff --tool ball:10 --ap 0.3 --ae 0.5 --tilt 25 --azimuth 35 --feed-angle 90 \\\n"
    "                --side left --vc 120 --radius\n"
    "  the paper's diagram, working diameter over the feed angle, as CSV:\n"
    "    vcpost deff --tool ball:10 --ap 1 --ae 1 --tilt 25 --azimuth 35 \\\n"
    "                --sweep feed-angle=0:360:15\n";

// The raw option values: everything is checked by hand in run() so that
// each error is one line naming the option.
struct DeffArguments {
  std::string tool, ap, ae, normal, tilt, azimuth, feed, feed_angle, side = "left";
  std::string vc, rpm, policy = "max", spindle = "cw", sweep, batch;
  bool json = false, radius = false;
};

std::string format_value(double value) {
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

CommandError usage(const std::string& option, const std::string& message) {
  return CommandError(option + ": " + message);
}

double number_option(const std::string& option, const std::string& text) {
  try {
    return parse_number(text);
  } catch (const vcpost::Error& e) {
    throw usage(option, e.what());
  }
}

Eigen::Vector3d vector_option(const std::string& option, const std::string& text,
                              const char* names) {
  try {
    return parse_vector(text, names);
  } catch (const vcpost::Error& e) {
    throw usage(option, e.what());
  }
}

// Which option to blame for a bad normal or feed: the vector option, the
// angle option or the sweep value they came from.
struct Blame {
  std::string normal, feed;
};

// Builds and checks one set-up, naming the option at fault.
Description described(const SetupRequest& request, const Blame& blame) {
  try {
    return describe(request);
  } catch (const SetupError& e) {
    switch (e.field()) {
      case SetupField::diameter:
        throw usage("--tool", e.what());
      case SetupField::ap:
        throw usage("--ap", e.what());
      case SetupField::ae:
        throw usage("--ae", e.what());
      case SetupField::normal:
        throw usage(blame.normal, e.what());
      case SetupField::feed:
        throw usage(blame.feed, e.what());
    }
    throw;
  }
}

// Writes the header and the rows with their result columns. The header goes
// out with the first good row (or at the end of an input without rows), so
// a bad first row leaves stdout empty; a later bad row stops the run with
// the rows before it written.
void stream_batch(std::istream& in, const std::string& source, bool radius) {
  BatchReader reader(in, source);
  bool header_written = false;
  const auto write_header = [&] {
    std::cout << reader.header() << ',' << csv_header(radius) << '\n';
    header_written = true;
  };
  BatchRow row;
  while (reader.next(row)) {
    const std::string cells = csv_cells(evaluate(row.tool, row.setup), radius);
    if (!header_written) write_header();
    std::cout << row.text << ',' << cells << '\n';
  }
  if (!header_written) write_header();
  if (in.bad()) throw vcpost::Error(Code::E2002, source + ": read error");
}

void run_batch(const DeffArguments& args) {
  try {
    if (args.batch == "-") return stream_batch(std::cin, "<stdin>", args.radius);
    std::ifstream file(args.batch);
    if (!file) {
      throw CommandError(Code::E2002, "--batch: cannot open '" + args.batch + "' for reading");
    }
    std::error_code error;
    if (std::filesystem::is_regular_file(args.batch, error)) {
      // A file can be read twice: check every row first (without holding
      // them), so a bad row anywhere leaves stdout empty.
      BatchReader check(file, args.batch);
      BatchRow row;
      while (check.next(row)) {
      }
      file.clear();
      file.seekg(0);
    }
    stream_batch(file, args.batch, args.radius);
  } catch (const vcpost::Error& e) {
    std::cout.flush();
    throw CommandError(e.code(), e.what());
  }
}

// Which options the user gave, and the refusals of two given together.
class Given {
 public:
  explicit Given(const CLI::App& command) : command_(command) {}
  bool operator()(const char* option) const { return command_.count(option) > 0; }
  void conflict(const char* first, const char* second, const std::string& why) const {
    if ((*this)(first) && (*this)(second)) {
      throw usage(first, std::string("cannot be combined with ") + second + " (" + why + ")");
    }
  }

 private:
  const CLI::App& command_;
};

// Options that cannot go together, or not with --batch or --sweep.
void check_combinations(const Given& given) {
  given.conflict("--sweep", "--batch", "a sweep varies one set-up, a batch reads many");
  given.conflict("--normal", "--tilt", "give the normal either as a vector or as angles");
  given.conflict("--normal", "--azimuth", "give the normal either as a vector or as angles");
  given.conflict("--feed", "--feed-angle", "give the feed either as a vector or as an angle");
  given.conflict("--vc", "--rpm", "give the nominal cutting speed or the spindle speed, not both");

  if (given("--batch")) {
    for (const char* option : {"--tool", "--ap", "--ae", "--normal", "--tilt", "--azimuth",
                               "--feed", "--feed-angle", "--side"}) {
      if (given(option)) {
        throw usage(option, "not used with --batch (each CSV row gives its own set-up)");
      }
    }
  }
  if (given("--batch") || given("--sweep")) {
    const char* mode = given("--batch") ? "--batch" : "--sweep";
    for (const char* option : {"--vc", "--rpm", "--policy", "--spindle", "--json"}) {
      if (given(option)) {
        throw usage(option, std::string("not used with ") + mode +
                                " (it writes the CSV result columns only)");
      }
    }
  }
}

// The one set-up of the options (before a swept angle is filled in).
SetupRequest read_setup(const Given& given, const DeffArguments& args) {
  for (const char* option : {"--tool", "--ap", "--ae"}) {
    if (!given(option)) throw usage(option, "required (see vcpost deff --help)");
  }
  if (given("--policy") && !given("--vc") && !given("--rpm")) {
    throw usage("--policy", "only used with --vc or --rpm");
  }

  SetupRequest request;
  try {
    request.tool = geometry::parse_tool(args.tool);
  } catch (const std::invalid_argument& e) {
    throw usage("--tool", e.what());
  }
  request.ap = number_option("--ap", args.ap);
  request.ae = number_option("--ae", args.ae);
  try {
    request.side = parse_side(args.side);
  } catch (const vcpost::Error& e) {
    throw usage("--side", e.what());
  }
  if (args.spindle == "cw") {
    request.spindle = geometry::SpindleDirection::clockwise;
  } else if (args.spindle == "ccw") {
    request.spindle = geometry::SpindleDirection::counter_clockwise;
  } else {
    throw usage("--spindle", "'" + args.spindle + "' is not a direction (expected cw or ccw)");
  }
  if (given("--normal")) request.normal = vector_option("--normal", args.normal, "nx,ny,nz");
  if (given("--tilt")) request.tilt_deg = number_option("--tilt", args.tilt);
  if (given("--azimuth")) request.azimuth_deg = number_option("--azimuth", args.azimuth);
  if (given("--feed")) request.feed = vector_option("--feed", args.feed, "fx,fy,fz");
  if (given("--feed-angle"))
    request.feed_angle_deg = number_option("--feed-angle", args.feed_angle);
  return request;
}

// --sweep: one CSV row per value of the swept angle, every set-up checked
// before anything is printed.
void run_sweep(const Given& given, const DeffArguments& args, const SetupRequest& request,
               const Blame& blame) {
  Sweep sweep;
  try {
    sweep = parse_sweep(args.sweep);
  } catch (const vcpost::Error& e) {
    throw usage("--sweep", e.what());
  }
  const std::string swept(to_string(sweep.parameter));
  if (sweep.parameter == SweepParameter::tilt) {
    given.conflict("--sweep", "--normal", "the sweep sets the normal's tilt");
    given.conflict("--sweep", "--tilt", "the sweep sets the tilt");
  } else if (sweep.parameter == SweepParameter::azimuth) {
    given.conflict("--sweep", "--normal", "the sweep sets the normal's azimuth");
    given.conflict("--sweep", "--azimuth", "the sweep sets the azimuth");
  } else {
    given.conflict("--sweep", "--feed", "the sweep sets the feed angle");
    given.conflict("--sweep", "--feed-angle", "the sweep sets the feed angle");
  }
  std::vector<std::pair<double, Description>> cases;
  for (const double value : sweep.values()) {
    SetupRequest at = request;
    Blame at_blame = blame;
    const std::string name = "--sweep: " + swept + " = " + format_value(value);
    switch (sweep.parameter) {
      case SweepParameter::tilt:
        at.tilt_deg = value;
        break;
      case SweepParameter::azimuth:
        at.azimuth_deg = value;
        break;
      case SweepParameter::feed_angle:
        at.feed_angle_deg = value;
        break;
    }
    // A bad tilt is the sweep's; a feed vector parallel to the normal at
    // some tilt or azimuth is the sweep value's as well.
    if (sweep.parameter == SweepParameter::tilt) at_blame.normal = name;
    at_blame.feed = name;
    cases.emplace_back(value, described(at, at_blame));
  }
  std::cout << csv_name(sweep.parameter) << ',' << csv_header(args.radius) << '\n';
  for (const auto& [value, description] : cases) {
    std::cout << format_value(value) << ','
              << csv_cells(evaluate(description.tool, description.setup), args.radius) << '\n';
  }
}

// --vc, --rpm and --policy.
SpeedRequest read_speed(const Given& given, const DeffArguments& args) {
  SpeedRequest speed_request;
  const auto policy = geometry::parse_diameter_policy(args.policy);
  if (!policy) {
    throw usage("--policy",
                "'" + args.policy + "' is not a policy (expected max, tangent or mean)");
  }
  speed_request.policy = *policy;
  if (given("--vc")) {
    speed_request.vc = number_option("--vc", args.vc);
    if (*speed_request.vc <= 0) throw usage("--vc", "the cutting speed must be > 0 m/min");
  }
  if (given("--rpm")) {
    speed_request.rpm = number_option("--rpm", args.rpm);
    if (*speed_request.rpm <= 0) throw usage("--rpm", "the spindle speed must be > 0 rpm");
  }
  return speed_request;
}

// One set-up: the table or the JSON object.
void run_one(const Given& given, const DeffArguments& args, const SetupRequest& request,
             const Blame& blame) {
  const Description description = described(request, blame);
  const SpeedRequest speed_request = read_speed(given, args);
  const Evaluation evaluation = evaluate(description.tool, description.setup);
  std::optional<Speed> speed;
  if (speed_request.vc || speed_request.rpm) speed = plan_speed(evaluation, speed_request);
  std::ostringstream out;
  if (args.json) {
    out << to_json(description, evaluation, speed).dump(2) << '\n';
  } else {
    write_table(out, description, evaluation, speed, args.radius);
  }
  std::cout << out.str();
}

void run(const CLI::App& command, const DeffArguments& args) {
  const Given given(command);
  check_combinations(given);
  if (given("--batch")) return run_batch(args);
  const SetupRequest request = read_setup(given, args);
  const Blame blame{given("--normal") ? "--normal" : "--tilt",
                    given("--feed") ? "--feed" : "--feed-angle"};
  if (given("--sweep")) return run_sweep(given, args, request, blame);
  run_one(given, args, request, blame);
}

}  // namespace

void add_deff_command(CLI::App& app) {
  auto* command = app.add_subcommand("deff", kDeffDescription);
  auto args = std::make_shared<DeffArguments>();
  command
      ->add_option("--tool", args->tool,
                   "tool, sizes in mm: ball:D, bull:D:rc or flat:D, e.g. ball:10 (required "
                   "unless --batch)")
      ->type_name("SPEC");
  command
      ->add_option("--ap", args->ap,
                   "depth of cut along the surface normal, mm, in (0, D) (required unless "
                   "--batch)")
      ->type_name("MM");
  command
      ->add_option("--ae", args->ae,
                   "width of cut (stepover) to the previous pass, on the surface, mm, >= 0 "
                   "(required unless --batch)")
      ->type_name("MM");
  command
      ->add_option("--normal", args->normal,
                   "unit surface normal at the contact point, out of the material, n_z > 0 "
                   "(default 0,0,1: horizontal); write --normal=-0.5,0,0.866 when it starts "
                   "with a minus")
      ->type_name("NX,NY,NZ");
  command
      ->add_option("--tilt", args->tilt,
                   "instead of --normal: tilt of the normal to +z (the paper's A_N2), degrees, "
                   "in (-90, 90) (default 0)")
      ->type_name("DEG");
  command
      ->add_option("--azimuth", args->azimuth,
                   "instead of --normal: azimuth of the normal's xy projection to +x (the "
                   "paper's A_N1), degrees (default 0)")
      ->type_name("DEG");
  command
      ->add_option("--feed", args->feed,
                   "feed direction, any length, projected onto the tangent plane (default "
                   "1,0,0)")
      ->type_name("FX,FY,FZ");
  command
      ->add_option("--feed-angle", args->feed_angle,
                   "instead of --feed: the paper's feed angle A, azimuth of the feed to +x, "
                   "degrees, projected onto the tangent plane (default 0)")
      ->type_name("DEG");
  command
      ->add_option("--side", args->side,
                   "side of the path the previous pass lies on, looking along the feed "
                   "(default left)")
      ->type_name("left|right");
  command
      ->add_option("--vc", args->vc,
                   "nominal cutting speed, m/min: print vc at each point and the spindle "
                   "speed n = 1000 vc / (pi D_ref) (default none)")
      ->type_name("M/MIN");
  command
      ->add_option("--rpm", args->rpm,
                   "spindle speed, 1/min: print vc at each point at this speed (default none)")
      ->type_name("RPM");
  command
      ->add_option("--policy", args->policy,
                   "D_ref for --vc/--rpm: max = D_max, tangent = the cutting point's 2r, "
                   "mean = D_mean (default max)")
      ->type_name("max|tangent|mean");
  command
      ->add_option("--spindle", args->spindle,
                   "spindle direction, cw = M3, ccw = M4; decides up/down milling "
                   "(default cw)")
      ->type_name("cw|ccw");
  command->add_flag("--radius", args->radius,
                    "also show r = 2r/2, the value the paper tabulates as 'working diameter'; "
                    "with --sweep/--batch append r_* columns (default off)");
  command->add_flag("--json", args->json,
                    "print one JSON object instead of the table (default off)");
  command
      ->add_option("--sweep", args->sweep,
                   "CSV over an angle, degrees, stop included when on the grid: "
                   "feed-angle=0:360:15, tilt=0:60:5 or azimuth=0:180:10 (default none)")
      ->type_name("NAME=START:STOP:STEP");
  command
      ->add_option("--batch", args->batch,
                   "CSV file of set-ups (columns d,ap,ae,nx,ny,nz,fx,fy,fz,side, optional "
                   "tool,rc), '-' for stdin; writes the rows with result columns (default "
                   "none)")
      ->type_name("FILE");
  command->callback([command, args] {
    standard_output_is_the_only_output();
    run(*command, *args);
  });
}

}  // namespace vcpost::cli
