#include "results_folder.hpp"

#include "cli.hpp"

#include <mechgraph/errors.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <ostream>
#include <string>
#include <unistd.h>

namespace mechgraph::cli {
namespace {

[[noreturn]] void io_failure(const std::string& what, const std::filesystem::path& path, int error) {
  throw IoError("cannot " + what + " '" + path.string() + "': " + std::strerror(error));
}

}  // namespace

void check_written(const std::ostream& stream, const std::filesystem::path& file) {
  if (!stream) throw IoError("cannot write '" + file.string() + "' (disk full or no permission?)");
}

void check_results_folder(const std::filesystem::path& dir, bool replace) {
  std::error_code ec;
  if (replace || !std::filesystem::exists(dir, ec)) return;
  if (!std::filesystem::is_directory(dir, ec)) io_failure("write results into", dir, ENOTDIR);
  if (!std::filesystem::is_empty(dir, ec))
    throw UsageError("the results folder '" + dir.string() + "' exists already: give --force to replace it, or another --out");
}

void write_results_folder(const std::filesystem::path& dir, bool replace,
                          const std::function<void(const std::filesystem::path& staging)>& write) {
  namespace fs = std::filesystem;
  std::error_code ec;
  check_results_folder(dir, replace);
  const bool exists = fs::exists(dir, ec);
  const fs::path parent = dir.has_parent_path() ? dir.parent_path() : fs::path(".");
  fs::create_directories(parent, ec);
  if (ec) io_failure("make the folder", parent, ec.value());
  const fs::path staging = parent / ("." + dir.filename().string() + ".staging-" + std::to_string(::getpid()));
  fs::remove_all(staging, ec);
  if (!fs::create_directory(staging, ec) || ec) io_failure("make the staging folder", staging, ec ? ec.value() : EEXIST);
  try {
    write(staging);
  } catch (...) {
    fs::remove_all(staging, ec);
    throw;
  }
  if (!exists) {
    if (std::rename(staging.c_str(), dir.c_str()) != 0) {
      const int error = errno;
      fs::remove_all(staging, ec);
      io_failure("move the results into", dir, error);
    }
    return;
  }
  // Swap old and new in one step; the staging path then holds the old results, removed after.
  if (::renameat2(AT_FDCWD, staging.c_str(), AT_FDCWD, dir.c_str(), RENAME_EXCHANGE) != 0) {
    const int error = errno;
    fs::remove_all(staging, ec);
    io_failure("replace the results in", dir, error);
  }
  fs::remove_all(staging, ec);
}

}  // namespace mechgraph::cli
