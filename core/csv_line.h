// One CSV record split into cells: RFC 4180 quoting ("" inside quotes is a
// quote), no line breaks inside cells. Header-only so the build-time
// generator of the error table (core/gen/), which core itself depends on,
// shares it with the readers of CSV input. No I/O, no exceptions: the
// caller words the error for its own input.
#pragma once

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vcpost::csv {

struct LineOptions {
  bool trim_blanks = false;       // spaces and tabs around a cell (and a quoted one) dropped
  bool quote_in_unquoted = true;  // a '"' inside an unquoted cell is a character (else an error)
};

enum class LineError { unterminated_quote, text_after_quote, quote_in_unquoted };

struct SplitLine {
  std::vector<std::string> cells;
  std::optional<LineError> error;  // cells then holds the ones before the bad one
  std::size_t error_cell = 0;      // 1-based cell of the error
};

inline SplitLine split_line(std::string_view line, LineOptions options = {}) {
  SplitLine out;
  const auto blank = [](char c) { return c == ' ' || c == '\t'; };
  const auto fail = [&out](LineError error) {
    out.error = error;
    out.error_cell = out.cells.size() + 1;
    return out;
  };
  std::size_t i = 0;
  for (;;) {
    std::string cell;
    if (options.trim_blanks) {
      while (i < line.size() && blank(line[i])) ++i;
    }
    if (i < line.size() && line[i] == '"') {
      ++i;
      for (;;) {
        if (i >= line.size()) return fail(LineError::unterminated_quote);
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            cell += '"';
            i += 2;
            continue;
          }
          ++i;
          break;
        }
        cell += line[i++];
      }
      if (options.trim_blanks) {
        while (i < line.size() && blank(line[i])) ++i;
      }
      if (i < line.size() && line[i] != ',') return fail(LineError::text_after_quote);
    } else {
      const std::size_t comma = std::min(line.find(',', i), line.size());
      std::string_view text = line.substr(i, comma - i);
      if (!options.quote_in_unquoted && text.find('"') != std::string_view::npos) {
        return fail(LineError::quote_in_unquoted);
      }
      if (options.trim_blanks) {
        while (!text.empty() && blank(text.back())) text.remove_suffix(1);
      }
      cell = text;
      i = comma;
    }
    out.cells.push_back(std::move(cell));
    if (i >= line.size()) return out;
    ++i;  // the comma
  }
}

}  // namespace vcpost::csv
