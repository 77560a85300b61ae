// Lexical layer of APT CL data: physical lines -> logical records, each with
// its major word, its parameters and their file positions.
//
// What it understands (ISO 4343 APT text, NX CLSF, Creo .ncl, CATIA APT):
// - `$` as the last non-blank character continues the record on the next line;
// - `$$` starts a comment (a whole line: a comment record; after a statement:
//   dropped);
// - `MAJOR/p1,p2,...` with blanks anywhere around words and commas, `MAJOR`
//   alone (RAPID, FINI), `MAJOR text` (PARTNO CORE_WORK), the two-word major
//   `TOOL PATH`, upper or lower case, LF, CRLF;
// - a line that starts with a number continues the coordinates of the
//   previous motion record (Creo writes multi-point GOTOs so).
// It streams: memory is bounded by the longest record, never by file length.
#pragma once

#include <cstdint>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

#include "postproc/cldata/cl_codes.h"
#include "postproc/program/events.h"

namespace vcpost::cldata {

// Largest magnitude a parameter may have to count as a number.
inline constexpr double kMaxClNumber = 1e12;

struct ClParam {
  std::string_view text;  // trimmed, as written (empty for ",,")
  double value = 0;       // valid when is_number: finite, |value| <= kMaxClNumber
  bool is_number = false;
  std::uint32_t line = 0;
  std::uint32_t column = 0;  // 1-based column of the parameter's first character
};

enum class ClRecordKind {
  statement,  // MAJOR[/params]
  points,     // a line of bare coordinates following a motion record
  comment,    // $$ ... (text = after the $$)
};

// One logical record. Views point into the reader's buffers and stay valid
// until the next call of ClRecordReader::next().
struct ClRecord {
  ClRecordKind kind = ClRecordKind::statement;
  std::string_view major;       // upper-cased, e.g. "GOTO", "TOOL PATH"; empty unless statement
  char separator = 0;           // what followed the major word: '/', ',', '=', ' ' or 0 (nothing)
  std::string_view text;        // everything after the separator, trimmed (continuations joined)
  std::vector<ClParam> params;  // `text` split at commas (statements and points)
  program::SourceRef source;    // line and column of the first character, byte offset

  bool is(std::string_view upper_major) const { return major == upper_major; }
};

struct ClLexOptions {
  // Longer physical lines are refused (E3101) rather than buffered.
  std::size_t max_line_length = 65536;
};

class ClRecordReader {
 public:
  // `in` must outlive the reader. file_name is used in error messages only.
  ClRecordReader(std::istream& in, std::string file_name, ClLexOptions options = {});

  // Reads the next record into `record`; false at the end of the input.
  // Throws ClError (E3101 line too long, E3102 invalid byte, E3106 `$` at
  // the end of the file).
  bool next(ClRecord& record);

  const std::string& file_name() const { return file_name_; }
  std::uint32_t line_number() const { return line_number_; }  // last physical line read

 private:
  bool read_line(std::string_view& line);
  // The next record's physical lines: a comment line fills `record`; a
  // statement's lines are joined into logical_ (`record_offset`: the file
  // offset of its first byte). Read::end at the end of the input.
  enum class Read { end, comment, statement };
  Read read_logical(ClRecord& record, std::uint64_t& record_offset);
  // The statement in logical_: points, or a major word and its text.
  void parse_statement(ClRecord& record, std::uint64_t record_offset);
  // The major word at the start of `all` into major_ ("TOOL PATH" as one);
  // returns where what follows it starts (past blanks). Throws E3117 where
  // there is none.
  std::size_t read_major(std::string_view all);
  [[noreturn]] void fail(Code code, std::uint32_t line, std::uint32_t column,
                         std::string message) const;
  void split_params(ClRecord& record, std::size_t text_begin);
  std::pair<std::uint32_t, std::uint32_t> position_of(std::size_t logical_offset) const;

  std::istream& in_;
  std::string file_name_;
  ClLexOptions options_;

  std::vector<char> buffer_;
  std::size_t begin_ = 0;  // start of unread data in buffer_
  std::size_t end_ = 0;    // end of valid data in buffer_
  bool eof_ = false;
  std::uint64_t offset_ = 0;  // file offset of buffer_[begin_]
  std::uint32_t line_number_ = 0;
  std::uint64_t line_offset_ = 0;  // file offset of the last line read

  // The logical record: content of its physical lines, and where each
  // piece came from.
  struct Segment {
    std::size_t logical_offset;
    std::uint32_t line;
    std::uint32_t column;  // column of the segment's first character
  };
  std::string logical_;
  std::vector<Segment> segments_;
  std::string major_;
};

}  // namespace vcpost::cldata
