#pragma once
// Files in tests: read one whole, write one whole, start from an empty folder. Shared by the tests
// that talk to the command line and by the hostile-input kit (tests/hostile/hostile_support.hpp).
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace mechgraph::testing {

/// The bytes of `file` ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Writes `text` to `file` as it is (binary); returns the file's path as text for a command line.
inline std::string write_file(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
  return file.string();
}

/// `parent`/`name`, emptied (created when missing).
inline std::filesystem::path fresh_dir(const std::filesystem::path& parent, const std::string& name) {
  const std::filesystem::path dir = parent / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// `name` in this process's own temporary folder `<prefix>_<pid>`: gone (a command that refuses an
/// existing --out folder may make it), its parent made.
inline std::filesystem::path absent_dir(const std::string& prefix, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir.parent_path());
  return dir;
}

/// The cells of a plain CSV file, row by row, split at every ',' (no quoting: the CSVs of our own
/// writers whose cells hold no comma).
inline std::vector<std::vector<std::string>> csv_cells(const std::filesystem::path& file) {
  std::istringstream in(slurp(file));
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

}  // namespace mechgraph::testing
