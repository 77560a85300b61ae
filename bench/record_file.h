// Plain records (trivially copyable structs of numbers) written to and read
// from a binary file as they lie in memory: the answers two builds of a
// bench write, compared record by record (mesh_contacts, tool_contacts).
// Same machine only; no header, no versioning.
#pragma once

#include <fstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace vcpost::bench {

// Whether every record reached the file.
template <class Record>
bool write_records(const std::string& name, const std::vector<Record>& records) {
  static_assert(std::is_trivially_copyable_v<Record>);
  std::ofstream file(name, std::ios::binary);
  file.write(reinterpret_cast<const char*>(records.data()),
             static_cast<std::streamsize>(records.size() * sizeof(Record)));
  return file.good();
}

// Throws std::runtime_error when the file cannot be read.
template <class Record>
std::vector<Record> read_records(const std::string& name) {
  static_assert(std::is_trivially_copyable_v<Record>);
  std::ifstream file(name, std::ios::binary | std::ios::ate);
  if (!file) throw std::runtime_error("cannot read " + name);
  const auto size = static_cast<std::size_t>(file.tellg());
  std::vector<Record> records(size / sizeof(Record));
  file.seekg(0);
  file.read(reinterpret_cast<char*>(records.data()),
            static_cast<std::streamsize>(records.size() * sizeof(Record)));
  return records;
}

}  // namespace vcpost::bench
