#pragma once
// Where the rows of a sweep go. On stdout, as they come. In a file (`--out FILE`), append-only:
// rows go to FILE.part, each flushed as it is written, and FILE.part becomes FILE by a rename
// when the last case is in, so FILE is complete or absent. Beside it FILE.json, the manifest,
// says which sweep the rows belong to (a fingerprint of the scene, the --set values, the cases
// and the columns), how many cases the whole sweep has, which shard this file holds, and whether
// it is complete. After a crash or kill -9, `--resume` cuts a half-written last line, checks that
// the rows are this sweep's first cases in order, and goes on from the next one: no case is lost
// or written twice. `mechgraph merge` reads the manifests to check that shards cover a sweep.
#include "sweep_rows.hpp"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace mechgraph::cli {

struct SweepManifest {
  std::string sweep;          // fingerprint, hex
  std::size_t cases = 0;      // in the whole sweep
  std::size_t shard = 0, shards = 1;
  bool complete = false;
  std::size_t rows = 0, failed = 0;
  std::string scene, origin;
  RowFormat format = RowFormat::csv;
};

/// Reads FILE.json beside `file`; throws UsageError naming it when absent or unreadable.
SweepManifest read_manifest(const std::filesystem::path& file);
std::filesystem::path manifest_path(const std::filesystem::path& file);

class SweepFile {
 public:
  /// Opens `out` (or stdout when empty). An existing FILE (or FILE.part without `resume`) is
  /// refused unless `force`.
  SweepFile(const std::filesystem::path& out, SweepManifest manifest, bool resume, bool force);
  ~SweepFile();

  /// With --resume: the header of the rows already written (empty if none) and their case numbers.
  const std::vector<std::string>& resumed_header() const { return resumed_header_; }
  const std::vector<std::size_t>& resumed_cases() const { return resumed_cases_; }
  std::size_t resumed_failed() const { return resumed_failed_; }

  void write(const std::string& text);  // whole lines; flushed
  /// Closes the file; when `complete`, FILE.part becomes FILE and the manifest says so.
  void finish(bool complete, std::size_t rows, std::size_t failed);
  bool to_stdout() const { return out_.empty(); }
  const std::filesystem::path& path() const { return out_; }

 private:
  void write_manifest();
  std::filesystem::path out_, part_;
  SweepManifest manifest_;
  std::FILE* file_ = nullptr;
  std::vector<std::string> resumed_header_;
  std::vector<std::size_t> resumed_cases_;
  std::size_t resumed_failed_ = 0;
};

}  // namespace mechgraph::cli
