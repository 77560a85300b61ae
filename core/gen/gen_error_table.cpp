// Build-time generator: reads the code table (core/error_codes.csv) and the
// group titles (core/error_groups.csv) and writes the enum of codes
// (core/code.h, vcpost::Code), the C++ table that core/error.cpp includes
// and the documentation page docs/errors.md.
// Refuses a table that breaks its own rules (duplicate or malformed code,
// empty text, a warning with a non-zero exit code), so a bad row fails the
// build instead of reaching a user.
//
// usage: gen_error_table CODES.csv GROUPS.csv OUT.h OUT.inc OUT.md
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/csv_line.h"

namespace {

struct Row {
  std::string code, name, exit, summary, hint;
  int line = 0;
};

[[noreturn]] void die(const std::string& where, const std::string& message) {
  std::cerr << where << ": error: " << message << '\n';
  std::exit(1);
}

// One CSV record (RFC 4180 quoting, no line breaks inside fields).
std::vector<std::string> split(const std::string& line, const std::string& where) {
  vcpost::csv::SplitLine split = vcpost::csv::split_line(line, {.quote_in_unquoted = false});
  if (!split.error) return std::move(split.cells);
  switch (*split.error) {
    case vcpost::csv::LineError::unterminated_quote:
      die(where, "quoted field not closed");
    case vcpost::csv::LineError::text_after_quote:
      die(where, "text after a closing quote");
    case vcpost::csv::LineError::quote_in_unquoted:
      die(where, "quote inside an unquoted field");
  }
  die(where, "unreadable record");
}

std::vector<std::vector<std::string>> read_csv(const std::string& path, const std::string& header,
                                               std::vector<int>& lines) {
  std::ifstream in(path);
  if (!in) die(path, "cannot open");
  std::string line;
  std::vector<std::vector<std::string>> rows;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1) {
      if (line != header) die(path + ":1", "header must be '" + header + "'");
      continue;
    }
    if (line.empty()) continue;
    rows.push_back(split(line, path + ":" + std::to_string(number)));
    lines.push_back(number);
  }
  return rows;
}

std::string cpp_literal(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + '"';
}

std::string md_cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

bool valid_code(const std::string& code) {
  if (code.size() != 5 || (code[0] != 'E' && code[0] != 'W')) return false;
  for (std::size_t i = 1; i < 5; ++i)
    if (!std::isdigit(static_cast<unsigned char>(code[i]))) return false;
  return true;
}

bool valid_name(const std::string& name) {
  if (name.empty() || !std::islower(static_cast<unsigned char>(name[0]))) return false;
  return std::ranges::all_of(name, [](char c) {
    return std::islower(static_cast<unsigned char>(c)) ||
           std::isdigit(static_cast<unsigned char>(c)) || c == '_';
  });
}

// The code table's rows, each checked against the table's rules and the
// rows before it.
std::vector<Row> read_codes(const std::string& codes_path) {
  std::vector<int> lines;
  std::vector<Row> rows;
  std::set<std::string> seen;
  std::string previous;
  for (const auto& cells : read_csv(codes_path, "code,name,exit,summary,hint", lines)) {
    const std::string where = codes_path + ":" + std::to_string(lines[rows.size()]);
    if (cells.size() != 5) die(where, "expected 5 fields, found " + std::to_string(cells.size()));
    Row r{cells[0], cells[1], cells[2], cells[3], cells[4], lines[rows.size()]};
    if (!valid_code(r.code)) die(where, "code '" + r.code + "' is not E or W and four digits");
    if (!seen.insert(r.code).second) die(where, "code " + r.code + " appears twice");
    // Order by number, the error before the warning of the same number.
    const std::string key = r.code.substr(1) + (r.code[0] == 'E' ? "0" : "1");
    if (!previous.empty() && key <= previous) die(where, "codes must be in ascending order");
    previous = key;
    if (!valid_name(r.name)) die(where, "name '" + r.name + "' is not snake_case");
    if (r.exit.size() != 1 || r.exit[0] < '0' || r.exit[0] > '3')
      die(where, "exit must be 0, 1, 2 or 3");
    if (r.code[0] == 'W' && r.exit != "0") die(where, "a warning exits 0");
    if (r.code[0] == 'E' && r.exit == "0") die(where, "an error does not exit 0");
    if (r.summary.empty() || r.hint.empty()) die(where, "summary and hint must not be empty");
    rows.push_back(r);
  }
  return rows;
}

// The groups' prefixes and titles, in the file's order.
using Groups = std::vector<std::pair<std::string, std::string>>;

Groups read_groups(const std::string& groups_path) {
  std::vector<int> group_lines;
  Groups groups;
  for (const auto& cells : read_csv(groups_path, "prefix,title", group_lines)) {
    const std::string where = groups_path + ":" + std::to_string(group_lines[groups.size()]);
    if (cells.size() != 2 || cells[0].empty() || cells[1].empty())
      die(where, "expected a prefix and a title");
    groups.emplace_back(cells[0], cells[1]);
  }
  return groups;
}

// The group of a code: the longest prefix of its number.
std::string group_of(const Row& r, const Groups& groups, const std::string& codes_path) {
  std::string best;
  for (const auto& [prefix, title] : groups) {
    if (r.code.compare(1, prefix.size(), prefix) == 0 && prefix.size() > best.size()) best = prefix;
  }
  if (best.empty()) die(codes_path + ":" + std::to_string(r.line), "no group for " + r.code);
  return best;
}

// core/code.h. The enumerators are named after the codes themselves: the
// name column is not unique (E1402 and W1402 are both unknown_m_code).
// Their values are the rows' positions, so a code's row is found by
// indexing.
std::string code_header(const std::vector<Row>& rows) {
  std::ostringstream header;
  header << "// Generated from core/error_codes.csv by core/gen/gen_error_table.cpp: do not edit.\n"
            "// Every diagnostic code of vcpost; a new one is a row of the CSV.\n"
            "#pragma once\n\n#include <cstddef>\n#include <cstdint>\n\nnamespace vcpost {\n\n"
            "enum class Code : std::uint16_t {\n";
  for (const auto& r : rows)
    header << "  " << r.code << ",  // " << r.name << ": " << r.summary << "\n";
  header << "};\n\ninline constexpr std::size_t kCodeCount = " << rows.size()
         << ";\n\n}  // namespace vcpost\n";
  return header.str();
}

// The table core/error.cpp includes, a row per code in the enum's order.
std::string code_table(const std::vector<Row>& rows) {
  std::ostringstream inc;
  inc << "// Generated from core/error_codes.csv by core/gen/gen_error_table.cpp: do not edit.\n";
  for (const auto& r : rows) {
    inc << "{Code::" << r.code << ", " << cpp_literal(r.code) << ", " << cpp_literal(r.name) << ", "
        << (r.code[0] == 'E' ? "Severity::error" : "Severity::warning") << ", " << r.exit << ", "
        << cpp_literal(r.summary) << ", " << cpp_literal(r.hint) << "},\n";
  }
  return inc.str();
}

// docs/errors.md: a table per group.
std::string errors_page(const std::vector<Row>& rows, const Groups& groups,
                        const std::string& codes_path) {
  std::ostringstream md;
  md << "# Diagnostic codes\n\n"
        "<!-- Generated from core/error_codes.csv by core/gen/gen_error_table.cpp: edit the CSV,\n"
        "     build, and copy build/release/docs/errors.md here (a test compares them). -->\n\n"
        "Every error and warning vcpost reports carries one of these codes, as\n"
        "`file:line:col: error[E1403]: message`. Codes are stable: they are never\n"
        "renumbered or reused. `vcpost explain CODE` prints a code's entry. The exit\n"
        "column is the exit status of `vcpost` when the code ends the run (0 for\n"
        "warnings, which do not end it; 1 for warnings turned into errors by\n"
        "`--strict` and for failed verifications; 2 for bad usage or input; 3 for\n"
        "internal errors).\n";
  std::string current;
  for (const auto& r : rows) {
    const std::string g = group_of(r, groups, codes_path);
    if (g != current) {
      current = g;
      for (const auto& [prefix, title] : groups)
        if (prefix == g) md << "\n## " << title << "\n\n";
      md << "| code | name | exit | meaning | what to do |\n| --- | --- | --- | --- | --- |\n";
    }
    md << "| " << r.code << " | `" << r.name << "` | " << r.exit << " | " << md_cell(r.summary)
       << " | " << md_cell(r.hint) << " |\n";
  }
  return md.str();
}

// Writes only when the content changed, so dependents do not rebuild.
void write_if_changed(const std::string& path, const std::string& text) {
  std::ifstream old(path, std::ios::binary);
  if (old) {
    std::ostringstream current_text;
    current_text << old.rdbuf();
    if (current_text.str() == text) return;
  }
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) die(path, "cannot write");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6) {
    std::cerr << "usage: gen_error_table CODES.csv GROUPS.csv OUT.h OUT.inc OUT.md\n";
    return 2;
  }
  const std::string codes_path = argv[1], groups_path = argv[2];
  const std::vector<Row> rows = read_codes(codes_path);
  const Groups groups = read_groups(groups_path);
  // All three made before any is written: a code without a group fails the
  // run with nothing written.
  const std::string header = code_header(rows), table = code_table(rows),
                    page = errors_page(rows, groups, codes_path);
  write_if_changed(argv[3], header);
  write_if_changed(argv[4], table);
  write_if_changed(argv[5], page);
  return 0;
}
