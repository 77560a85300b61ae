// What the golden tests share (tests/golden/README.md): files read whole,
// and the stored form of a written program (whole when short, else its
// size, digest, first and last lines).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace vcpost::golden {

std::string read(const std::filesystem::path& path);  // empty when absent
std::string trimmed(std::string s);                   // without trailing blanks and newlines

// FNV-1a, 64 bits, as 16 hex digits: a stable digest with no dependency.
std::string digest(std::string_view text);

// Lines with their newlines.
std::vector<std::string_view> lines_of(std::string_view text);

// A program of more than 150 lines is stored as "lines L bytes B fnv1a64
// D", then its first and last 25 lines.
std::string stored_program(const std::string& program);

// Whether the expected files are to be rewritten (VCPOST_GOLDEN_UPDATE set).
bool updating();

}  // namespace vcpost::golden
