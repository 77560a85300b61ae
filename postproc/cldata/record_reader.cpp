#include "postproc/cldata/record_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

#include "core/text.h"

namespace vcpost::cldata {

namespace {

constexpr std::size_t chunk_size = 1 << 16;

bool is_blank(char c) { return c == ' ' || c == '\t'; }

bool is_word_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

bool starts_number(char c) { return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.'; }

// Majors whose parameter is free text, kept as written.
bool is_text_major(std::string_view major) {
  return major == "PARTNO" || major == "PPRINT" || major == "INSERT" || major == "TPRINT";
}

std::string byte_name(unsigned char c) {
  static constexpr char hex[] = "0123456789ABCDEF";
  std::string s = "0x";
  s += hex[c >> 4];
  s += hex[c & 15];
  return s;
}

}  // namespace

ClRecordReader::ClRecordReader(std::istream& in, std::string file_name, ClLexOptions options)
    : in_(in), file_name_(std::move(file_name)), options_(options) {
  buffer_.resize(chunk_size);
}

void ClRecordReader::fail(Code code, std::uint32_t line, std::uint32_t column,
                          std::string message) const {
  throw ClError(ClDiagnostic{code, line, column, std::move(message)}, file_name_);
}

// One physical line without its line end. Control bytes other than tab (and
// the CR of CRLF) are refused here, so every later stage sees clean text.
bool ClRecordReader::read_line(std::string_view& line) {
  std::size_t scan = begin_;
  while (true) {
    const char* data = buffer_.data();
    const void* nl = scan < end_ ? std::memchr(data + scan, '\n', end_ - scan) : nullptr;
    if (nl != nullptr || (eof_ && begin_ < end_)) {
      const std::size_t stop =
          nl != nullptr ? static_cast<std::size_t>(static_cast<const char*>(nl) - data) : end_;
      std::size_t length = stop - begin_;
      ++line_number_;
      line_offset_ = offset_;
      if (length > options_.max_line_length) {
        fail(Code::E3101, line_number_, 1,
             "line of " + std::to_string(length) + " bytes is longer than the limit of " +
                 std::to_string(options_.max_line_length));
      }
      if (length > 0 && data[begin_ + length - 1] == '\r') --length;
      for (std::size_t i = 0; i < length; ++i) {
        const auto c = static_cast<unsigned char>(data[begin_ + i]);
        if ((c < 0x20 && c != '\t') || c == 0x7F) {
          fail(Code::E3102, line_number_, static_cast<std::uint32_t>(i + 1),
               "invalid byte " + byte_name(c) + " in CL data");
        }
      }
      line = std::string_view(data + begin_, length);
      const std::size_t consumed = (nl != nullptr ? stop + 1 : stop) - begin_;
      begin_ += consumed;
      offset_ += consumed;
      return true;
    }
    if (eof_) return false;
    // Need more data: keep the unread tail, refuse a line that cannot end
    // within the limit instead of buffering it.
    const std::size_t pending = end_ - begin_;
    if (pending > options_.max_line_length + 1) {
      fail(Code::E3101, line_number_ + 1, 1,
           "line longer than the limit of " + std::to_string(options_.max_line_length) + " bytes");
    }
    if (begin_ > 0) {
      std::memmove(buffer_.data(), buffer_.data() + begin_, pending);
      begin_ = 0;
      end_ = pending;
    }
    if (buffer_.size() - end_ < chunk_size / 2) buffer_.resize(buffer_.size() * 2);
    scan = end_;
    in_.read(buffer_.data() + end_, static_cast<std::streamsize>(buffer_.size() - end_));
    const auto got = static_cast<std::size_t>(in_.gcount());
    end_ += got;
    if (got == 0) eof_ = true;
  }
}

std::pair<std::uint32_t, std::uint32_t> ClRecordReader::position_of(
    std::size_t logical_offset) const {
  auto it =
      std::upper_bound(segments_.begin(), segments_.end(), logical_offset,
                       [](std::size_t off, const Segment& s) { return off < s.logical_offset; });
  const Segment& s = *(it - 1);
  return {s.line, s.column + static_cast<std::uint32_t>(logical_offset - s.logical_offset)};
}

void ClRecordReader::split_params(ClRecord& record, std::size_t text_begin) {
  record.params.clear();
  const std::string_view all(logical_);
  if (trim(all.substr(text_begin), kBlanks).empty()) return;
  std::size_t start = text_begin;
  while (true) {
    std::size_t stop = all.find(',', start);
    if (stop == std::string_view::npos) stop = all.size();
    std::size_t b = start;
    std::size_t e = stop;
    while (b < e && is_blank(all[b])) ++b;
    while (e > b && is_blank(all[e - 1])) --e;
    ClParam p;
    p.text = all.substr(b, e - b);
    const auto [line, column] = position_of(b);
    p.line = line;
    p.column = column;
    for (std::size_t i = b; i < e; ++i) {
      if (static_cast<unsigned char>(all[i]) >= 0x80) {
        const auto [l, c] = position_of(i);
        fail(Code::E3102, l, c,
             "invalid byte " + byte_name(static_cast<unsigned char>(all[i])) + " in a parameter");
      }
    }
    if (!p.text.empty() && starts_number(p.text.front())) {
      std::string_view t = p.text;
      if (t.front() == '+') t.remove_prefix(1);
      double v = 0;
      const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
      // "inf" and "nan" parse, but are no coordinates: left as bad numbers,
      // as is a magnitude beyond 1e12, whose inch conversions, sums and
      // squares would overflow (the G-code reader's kMaxWordMagnitude).
      if (r.ec == std::errc() && r.ptr == t.data() + t.size() && std::abs(v) <= kMaxClNumber) {
        p.value = v;
        p.is_number = true;
      }
    }
    record.params.push_back(p);
    if (stop == all.size()) break;
    start = stop + 1;
  }
}

bool ClRecordReader::next(ClRecord& record) {
  std::uint64_t record_offset = 0;
  switch (read_logical(record, record_offset)) {
    case Read::end:
      return false;
    case Read::comment:
      return true;
    case Read::statement:
      break;
  }
  parse_statement(record, record_offset);
  return true;
}

ClRecordReader::Read ClRecordReader::read_logical(ClRecord& record, std::uint64_t& record_offset) {
  logical_.clear();
  segments_.clear();
  std::string_view line;
  bool continued = false;
  while (true) {
    if (!read_line(line)) {
      if (continued) {
        fail(Code::E3106, line_number_, 1, "the file ends inside a record continued with '$'");
      }
      return Read::end;
    }
    std::size_t first = 0;
    while (first < line.size() && is_blank(line[first])) ++first;
    if (first == line.size()) continue;  // blank line, inside a continuation or not
    const std::string_view content = line.substr(first);
    if (content.size() >= 2 && content[0] == '$' && content[1] == '$') {
      if (continued) continue;  // comment line between continued lines
      record = ClRecord{};
      record.kind = ClRecordKind::comment;
      record.text = trim(content.substr(2), kBlanks);
      record.source = {line_number_, static_cast<std::uint32_t>(first + 1), line_offset_};
      return Read::comment;
    }
    // Drop a trailing "$$ comment", then look for the '$' continuation mark.
    std::string_view body = content;
    if (const auto cc = body.find("$$"); cc != std::string_view::npos) body = body.substr(0, cc);
    while (!body.empty() && is_blank(body.back())) body.remove_suffix(1);
    bool continues = false;
    if (!body.empty() && body.back() == '$') {
      continues = true;
      body.remove_suffix(1);
    }
    if (!continued) record_offset = line_offset_ + first;
    segments_.push_back({logical_.size(), line_number_, static_cast<std::uint32_t>(first + 1)});
    logical_.append(body);
    if (!continues) return Read::statement;
    logical_ += ' ';
    continued = true;
  }
}

void ClRecordReader::parse_statement(ClRecord& record, std::uint64_t record_offset) {
  record.kind = ClRecordKind::statement;
  record.major = {};
  record.separator = 0;
  record.text = {};
  record.source = {segments_.front().line, segments_.front().column, record_offset};
  const std::string_view all(logical_);

  if (starts_number(all.front())) {
    record.kind = ClRecordKind::points;
    record.text = trim(all, kBlanks);
    split_params(record, 0);
    return;
  }
  const std::size_t j = read_major(all);
  record.major = major_;
  std::size_t text_begin = j;
  if (j < all.size() && (all[j] == '/' || all[j] == ',' || all[j] == '=')) {
    record.separator = all[j];
    text_begin = j + 1;
  } else if (j < all.size()) {
    record.separator = ' ';
  }
  record.text = trim(all.substr(text_begin), kBlanks);
  if (is_text_major(major_) || record.separator == '=') {
    record.params.clear();
  } else {
    split_params(record, text_begin);
  }
}

std::size_t ClRecordReader::read_major(std::string_view all) {
  std::size_t i = 0;
  major_.clear();
  while (i < all.size() && is_word_char(all[i])) major_ += ascii_upper(all[i++]);
  std::size_t j = i;
  while (j < all.size() && is_blank(all[j])) ++j;
  if (major_ == "TOOL" && all.size() - j >= 4) {
    std::string second;
    for (std::size_t k = j; k < j + 4; ++k) second += ascii_upper(all[k]);
    if (second == "PATH") {
      major_ += " PATH";
      i = j + 4;
      j = i;
      while (j < all.size() && is_blank(all[j])) ++j;
    }
  }
  if (major_.empty()) {
    const auto [l, c] = position_of(0);
    fail(Code::E3117, l, c,
         "record does not start with a major word: '" + std::string(all.substr(0, 20)) + "'");
  }
  return j;
}

}  // namespace vcpost::cldata
