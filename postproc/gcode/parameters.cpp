#include "postproc/gcode/parameters.h"

#include <algorithm>
#include <array>

namespace vcpost::gcode {

namespace {

// RS274NGC numbered parameters run to 5602; from 5000 on they are the
// control's (offsets, tool data, positions).
constexpr int kNgcLast = 5602;
constexpr int kNgcMachineFirst = 5000;
constexpr int kFanucSystemFirst = 1000;
constexpr int kFanucLast = 999;

// LinuxCNC's predefined named parameters (interp_namedparams.cc), sorted.
constexpr std::array<std::string_view, 60> kPredefined = {"_a",
                                                          "_abs_a",
                                                          "_abs_b",
                                                          "_abs_c",
                                                          "_abs_u",
                                                          "_abs_v",
                                                          "_abs_w",
                                                          "_abs_x",
                                                          "_abs_y",
                                                          "_abs_z",
                                                          "_absolute",
                                                          "_adaptive_feed",
                                                          "_b",
                                                          "_c",
                                                          "_call_level",
                                                          "_ccomp",
                                                          "_control_mode",
                                                          "_coord_system",
                                                          "_current_pocket",
                                                          "_current_tool",
                                                          "_feed",
                                                          "_feed_hold",
                                                          "_feed_override",
                                                          "_flood",
                                                          "_ijk_absolute_mode",
                                                          "_imperial",
                                                          "_incremental",
                                                          "_inverse_time",
                                                          "_lathe_diameter_mode",
                                                          "_lathe_radius_mode",
                                                          "_line",
                                                          "_metric",
                                                          "_mist",
                                                          "_motion_mode",
                                                          "_plane",
                                                          "_remap_level",
                                                          "_retract_old_z",
                                                          "_retract_r_plane",
                                                          "_rpm",
                                                          "_selected_pocket",
                                                          "_selected_tool",
                                                          "_speed_override",
                                                          "_spindle_css_mode",
                                                          "_spindle_cw",
                                                          "_spindle_on",
                                                          "_spindle_rpm_mode",
                                                          "_task",
                                                          "_tool_offset",
                                                          "_u",
                                                          "_units_per_minute",
                                                          "_units_per_rev",
                                                          "_v",
                                                          "_value",
                                                          "_value_returned",
                                                          "_vmajor",
                                                          "_vminor",
                                                          "_w",
                                                          "_x",
                                                          "_y",
                                                          "_z"};
static_assert(std::is_sorted(kPredefined.begin(), kPredefined.end()));

Access refuse(Code code, std::string message) {
  Access a;
  a.ok = false;
  a.code = code;
  a.message = std::move(message);
  return a;
}

}  // namespace

Parameters::Parameters(const Dialect& dialect) : kind_(dialect.kind), frames_(1) {
  const int size = kind_ == machines::Dialect::rs274ngc ? kNgcLast + 1 : kFanucLast + 1;
  globals_.assign(static_cast<std::size_t>(size), Value{0.0, kind_ != machines::Dialect::rs274ngc});
  set_.assign(static_cast<std::size_t>(size), false);
  for (auto& v : frames_.back().locals) v.vacant = kind_ != machines::Dialect::rs274ngc;
}

Access Parameters::read(int number) const {
  std::string name = "#";
  name += std::to_string(number);
  if (kind_ == machines::Dialect::rs274ngc) {
    if (number < 1 || number > kNgcLast)
      return refuse(Code::E1203, "parameter " + name + " does not exist");
    if (number <= local_count()) return {true, {}, {}, frames_.back().locals[number]};
    if (number >= kNgcMachineFirst && !set_[number])
      return refuse(Code::E1204, "parameter " + name +
                                     " holds machine state (offsets, tool or position) "
                                     "that only the running control knows");
    return {true, {}, {}, globals_[number]};
  }
  if (number == 0) return {true, {}, {}, Value{0.0, true}};
  if (number >= kFanucSystemFirst)
    return refuse(Code::E1204, "system variable " + name +
                                   " holds machine state that only the running control "
                                   "knows");
  if (number <= local_count()) return {true, {}, {}, frames_.back().locals[number]};
  if ((number >= 100 && number <= 199) || (number >= 500 && number <= kFanucLast))
    return {true, {}, {}, globals_[number]};
  return refuse(Code::E1203, "variable " + name + " does not exist");
}

Access Parameters::read(std::string_view name) const {
  const std::string key(name);
  if (!key.empty() && key[0] == '_') {
    if (auto it = global_named_.find(key); it != global_named_.end())
      return {true, {}, {}, Value{it->second, false}};
  } else if (auto it = frames_.back().named.find(key); it != frames_.back().named.end()) {
    return {true, {}, {}, Value{it->second, false}};
  }
  return refuse(Code::E1202,
                "named parameter #<" + key + "> is read before it is set" +
                    (key.empty() || key[0] != '_' ? std::string()
                                                  : " (predefined #<_...> parameters are machine "
                                                    "state and are not known to vcpost)"));
}

bool Parameters::exists(std::string_view name) const {
  if (read(name).ok) return true;
  return kind_ == machines::Dialect::rs274ngc &&
         std::binary_search(kPredefined.begin(), kPredefined.end(), name);
}

Access Parameters::write(int number, double value) {
  std::string name = "#";
  name += std::to_string(number);
  if (kind_ == machines::Dialect::rs274ngc) {
    if (number < 1 || number > kNgcLast)
      return refuse(Code::E1203, "parameter " + name + " does not exist");
    if (number <= local_count()) {
      frames_.back().locals[number] = Value{value, false};
      return {};
    }
    globals_[number] = Value{value, false};
    set_[number] = true;
    return {};
  }
  if (number >= kFanucSystemFirst)
    return refuse(Code::E1204,
                  "writing system variable " + name +
                      " acts on the running control (alarm, message, offsets); vcpost cannot "
                      "follow it");
  if (number >= 1 && number <= local_count()) {
    frames_.back().locals[number] = Value{value, false};
    return {};
  }
  if ((number >= 100 && number <= 199) || (number >= 500 && number <= kFanucLast)) {
    globals_[number] = Value{value, false};
    set_[number] = true;
    return {};
  }
  return refuse(Code::E1203, "variable " + name + " cannot be written");
}

Access Parameters::write(std::string_view name, double value) {
  if (kind_ == machines::Dialect::rs274ngc &&
      std::binary_search(kPredefined.begin(), kPredefined.end(), name))
    return refuse(Code::E1204, "predefined parameter #<" + std::string(name) +
                                   "> is read-only: it reports the control's state");
  const std::string key(name);
  if (!key.empty() && key[0] == '_')
    global_named_[key] = value;
  else
    frames_.back().named[key] = value;
  return {};
}

void Parameters::push_frame(const std::vector<double>& arguments) {
  frames_.emplace_back();
  auto& locals = frames_.back().locals;
  for (auto& v : locals) v = Value{0.0, kind_ != machines::Dialect::rs274ngc};
  for (std::size_t i = 0; i < arguments.size() && i + 1 < locals.size(); ++i)
    locals[i + 1] = Value{arguments[i], false};
}

void Parameters::pop_frame() {
  if (frames_.size() > 1) frames_.pop_back();
}

}  // namespace vcpost::gcode
