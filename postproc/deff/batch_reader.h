// The batch input of the working-diameter evaluation (`vcpost deff --batch`): a CSV file of cutting
// set-ups, read one row at a time so a file of any length streams through.
//
// Header (first non-blank line) names the columns, in any order:
//   required d, ap, ae, nx, ny, nz, fx, fy, fz, side
//   optional tool (ball | bull | flat, default ball), rc (corner radius of
//   a bull-nose tool); any other column is carried along untouched.
// Units mm; side is left or right; (nx, ny, nz) a unit normal; (fx, fy, fz)
// a feed direction of any length. Cells may be quoted ("a, b"); blank lines
// are skipped; a CR before the line end and a UTF-8 byte-order mark are
// ignored.
#pragma once

#include <cstddef>
#include <istream>
#include <map>
#include <string>
#include <vector>

#include "geometry/engagement.h"
#include "geometry/tool.h"

namespace vcpost::deff {

struct BatchRow {
  std::size_t line = 0;  // 1-based line number in the input
  std::string text;      // the row as given, without the line end
  geometry::Tool tool;
  geometry::CutSetup setup;  // checked (checked_setup), normal of unit length
};

// Splits one CSV line into cells, unquoting quoted cells ("" is a quote) and
// trimming blanks around unquoted ones. Throws vcpost::Error (E2006) for an unterminated
// quote or text after a closing quote.
std::vector<std::string> split_csv_line(const std::string& line);

class BatchReader {
 public:
  // Reads the header. `source` names the input in messages (the path as the
  // user gave it, or "<stdin>"). Throws vcpost::Error (E2006) "source:line: ..." for an
  // empty input, a missing, empty or repeated column name.
  // The stream must outlive the reader.
  BatchReader(std::istream& in, std::string source);

  const std::string& header() const { return header_; }

  // Reads and checks the next data row; false at the end of the input.
  // Throws vcpost::Error (E2006) "source:line: column 'ap': ..." for a wrong cell
  // count, a value that is not a number or is out of range (checked_setup),
  // an unknown tool or a missing corner radius.
  bool next(BatchRow& row);

 private:
  bool read_line(std::string& line);
  double number(const std::vector<std::string>& cells, const std::string& column) const;
  std::string where() const;

  std::istream* in_;
  std::string source_;
  std::size_t line_ = 0;
  std::string header_;
  std::size_t cell_count_ = 0;
  std::map<std::string, std::size_t> columns_;
};

}  // namespace vcpost::deff
