// Parameters (variables) of RS274NGC and Fanuc/Mazak macros, as far as a
// program computes them itself. What only the running control knows
// (positions, offsets, tool data, alarms: #5000+ in RS274NGC, #1000+ in
// Fanuc) is refused with Code::E1204, never guessed.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "postproc/gcode/diagnostics.h"
#include "postproc/gcode/dialect.h"

namespace vcpost::gcode {

// A value; `vacant` is Fanuc's <vacant> (#0, unset locals): 0 in arithmetic,
// equal only to another vacant value in EQ/NE. RS274NGC values never are.
struct Value {
  double number = 0.0;
  bool vacant = false;
};

// The result of a parameter access: ok, or the code and message of the
// refusal (the reader adds the position).
struct Access {
  bool ok = true;
  Code code = Code::E1201;
  std::string message;
  Value value;
};

class Parameters {
 public:
  explicit Parameters(const Dialect& dialect);

  Access read(int number) const;
  Access read(std::string_view name) const;  // name already normalised (lower case, no blanks)
  // EXISTS[#<name>]: set by the program, or one of LinuxCNC's predefined
  // read-only parameters (#<_x>, #<_metric> ...), which exist although
  // only the running control knows their values.
  bool exists(std::string_view name) const;
  Access write(int number, double value);
  Access write(std::string_view name, double value);

  // Subroutine frames: locals #1..#30 (#1..#33 Fanuc) and local named
  // parameters are saved on call and restored on return.
  void push_frame(const std::vector<double>& arguments);
  void pop_frame();
  std::size_t depth() const { return frames_.size(); }

 private:
  struct Frame {
    std::array<Value, 34> locals{};
    std::unordered_map<std::string, double> named;
  };
  machines::Dialect kind_;
  std::vector<Value> globals_;  // index = parameter number
  std::vector<bool> set_;
  std::vector<Frame> frames_;
  std::unordered_map<std::string, double> global_named_;
  int local_count() const { return kind_ == machines::Dialect::rs274ngc ? 30 : 33; }
};

}  // namespace vcpost::gcode
