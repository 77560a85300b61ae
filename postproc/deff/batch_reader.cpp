#include "postproc/deff/batch_reader.h"

#include <array>
#include <utility>

#include "core/csv_line.h"
#include "postproc/deff/setup_input.h"

namespace vcpost::deff {
namespace {

constexpr std::array<const char*, 10> kRequired = {"d",  "ap", "ae", "nx", "ny",
                                                   "nz", "fx", "fy", "fz", "side"};

std::string column_label(SetupField field) {
  switch (field) {
    case SetupField::diameter:
      return "column 'd'";
    case SetupField::ap:
      return "column 'ap'";
    case SetupField::ae:
      return "column 'ae'";
    case SetupField::normal:
      return "columns 'nx,ny,nz'";
    case SetupField::feed:
      return "columns 'fx,fy,fz'";
  }
  return "?";
}

}  // namespace

std::vector<std::string> split_csv_line(const std::string& line) {
  csv::SplitLine split = csv::split_line(line, {.trim_blanks = true, .quote_in_unquoted = true});
  if (!split.error) return std::move(split.cells);
  if (*split.error == csv::LineError::unterminated_quote) {
    throw vcpost::Error(Code::E2006, "unterminated quoted cell");
  }
  throw vcpost::Error(Code::E2006,
                      "text after a closing quote in cell " + std::to_string(split.error_cell));
}

BatchReader::BatchReader(std::istream& in, std::string source)
    : in_(&in), source_(std::move(source)) {
  if (!read_line(header_)) {
    throw vcpost::Error(Code::E2006, source_ +
                                         ": empty input, expected a header row with the columns "
                                         "d,ap,ae,nx,ny,nz,fx,fy,fz,side");
  }
  // A byte-order mark is what spreadsheet programs put before the header.
  if (header_.rfind("\xEF\xBB\xBF", 0) == 0) header_.erase(0, 3);
  std::vector<std::string> names;
  try {
    names = split_csv_line(header_);
  } catch (const vcpost::Error& e) {
    throw vcpost::Error(Code::E2006, where() + e.what());
  }
  cell_count_ = names.size();
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i].empty()) {
      throw vcpost::Error(Code::E2006,
                          where() + "header cell " + std::to_string(i + 1) + " is empty");
    }
    if (!columns_.emplace(names[i], i).second) {
      throw vcpost::Error(Code::E2006, where() + "column '" + names[i] + "' appears twice");
    }
  }
  for (const char* name : kRequired) {
    if (!columns_.contains(name)) {
      throw vcpost::Error(Code::E2006,
                          where() + "missing column '" + name +
                              "' (the header needs d,ap,ae,nx,ny,nz,fx,fy,fz,side in any order)");
    }
  }
}

bool BatchReader::read_line(std::string& line) {
  while (std::getline(*in_, line)) {
    ++line_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") != std::string::npos) return true;
  }
  return false;
}

std::string BatchReader::where() const { return source_ + ":" + std::to_string(line_) + ": "; }

double BatchReader::number(const std::vector<std::string>& cells, const std::string& column) const {
  try {
    return parse_number(cells[columns_.at(column)]);
  } catch (const vcpost::Error& e) {
    throw vcpost::Error(Code::E2006, where() + "column '" + column + "': " + e.what());
  }
}

bool BatchReader::next(BatchRow& row) {
  std::string text;
  if (!read_line(text)) return false;
  std::vector<std::string> cells;
  try {
    cells = split_csv_line(text);
  } catch (const vcpost::Error& e) {
    throw vcpost::Error(Code::E2006, where() + e.what());
  }
  if (cells.size() != cell_count_) {
    throw vcpost::Error(Code::E2006, where() + "expected " + std::to_string(cell_count_) +
                                         " cells as in the header, found " +
                                         std::to_string(cells.size()));
  }

  const double diameter = number(cells, "d");
  geometry::CutSetup setup;
  setup.ap = number(cells, "ap");
  setup.ae = number(cells, "ae");
  setup.normal = {number(cells, "nx"), number(cells, "ny"), number(cells, "nz")};
  setup.feed = {number(cells, "fx"), number(cells, "fy"), number(cells, "fz")};
  try {
    setup.side = parse_side(cells[columns_.at("side")]);
  } catch (const vcpost::Error& e) {
    throw vcpost::Error(Code::E2006, where() + "column 'side': " + e.what());
  }

  if (!(diameter > 0)) {
    throw vcpost::Error(Code::E2006, where() +
                                         "column 'd': the tool diameter must be > 0 mm, got '" +
                                         cells[columns_.at("d")] + "'");
  }
  const auto tool_column = columns_.find("tool");
  const std::string kind = tool_column == columns_.end() ? "" : cells[tool_column->second];
  const auto rc_column = columns_.find("rc");
  const bool has_rc = rc_column != columns_.end() && !cells[rc_column->second].empty();
  geometry::Tool tool;
  if (kind.empty() || kind == "ball" || kind == "flat") {
    if (has_rc) {
      throw vcpost::Error(Code::E2006,
                          where() +
                              "column 'rc': only a bull tool takes a corner radius, this row's "
                              "tool is " +
                              (kind.empty() ? std::string("ball") : kind));
    }
    tool = kind == "flat" ? geometry::Tool::flat(diameter) : geometry::Tool::ball(diameter);
  } else if (kind == "bull") {
    if (!has_rc) {
      throw vcpost::Error(Code::E2006,
                          where() + "column 'rc': a bull tool needs its corner radius");
    }
    const double corner = number(cells, "rc");
    if (!(corner > 0 && corner <= diameter / 2)) {
      throw vcpost::Error(Code::E2006,
                          where() + "column 'rc': the corner radius must lie in (0, d/2], got '" +
                              cells[rc_column->second] + "'");
    }
    // A corner that fills the radius is the ball end.
    tool = corner == diameter / 2 ? geometry::Tool::ball(diameter)
                                  : geometry::Tool::bull_nose(diameter, corner);
  } else {
    throw vcpost::Error(Code::E2006, where() + "column 'tool': unknown tool '" + kind +
                                         "' (expected ball, bull or flat)");
  }

  try {
    row.setup = checked_setup(tool, setup);
  } catch (const SetupError& e) {
    throw vcpost::Error(Code::E2006, where() + column_label(e.field()) + ": " + e.what());
  }
  row.tool = tool;
  row.line = line_;
  row.text = std::move(text);
  return true;
}

}  // namespace vcpost::deff
