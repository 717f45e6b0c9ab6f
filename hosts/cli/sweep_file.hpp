#pragma once
// Where the rows of a sweep go. On stdout, as they come. In a file (`--out FILE`), append-only:
// rows go to FILE.part, each flushed as it is written, and FILE.part becomes FILE by a rename
// when the last case is in, so FILE is complete or absent. Beside it FILE.json, the manifest,
// says which sweep the rows belong to (a fingerprint of the scene, the --set values, the cases
// and the columns), how many cases the whole sweep has, which shard this file holds, and whether
// it is complete. After a crash or kill -9, `--resume` cuts a half-written last line, checks that
// the rows are this sweep's first cases in order, and goes on from the next one: no case is lost
// or written twice. `mechgraph merge` reads the manifests to check that shards cover a sweep.
//
// Hostile folders (issue 18): FILE.lock is flocked for the whole run, so a second sweep (or a
// merge) writing FILE is refused naming the first's pid; FILE.part is created O_EXCL|O_NOFOLLOW
// and reopened for --resume O_NOFOLLOW as a regular file of this user, so a planted symlink of
// that name is refused, its target never written or truncated; the manifest is written whole
// through a temporary with an unpredictable name (write_file_whole). `--force` replaces FILE only
// when its manifest says mechgraph wrote it, and never anything but a regular file. Every row
// --resume carries over is checked (RowChecker). Reads are bounded: a manifest at most 64 KiB, a
// row at most max_row_bytes (rows files are read a line at a time), regular files only.
#include "output_file.hpp"
#include "cli.hpp"

#include <mechgraph/host/sweep_rows.hpp>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace mechgraph::cli {

/// How this mechgraph writes a sweep's rows and fingerprints its cases, recorded in each manifest
/// ("rows_format"); raised whenever a case's cells or the fingerprint change. 2: grid points
/// spaced in the range's unit at 15 significant digits, generated values in the fewest digits
/// that read back. Manifests written before the key existed do not say: their rows are format 1
/// (grid points spaced in SI, offset units at 17 digits) or, from the builds just before the key,
/// already format 2; only their rows themselves can tell.
inline constexpr std::size_t rows_format_written = 2;

struct SweepManifest {
  std::string sweep;          // fingerprint, hex
  std::optional<std::size_t> rows_format = rows_format_written;  // absent: the manifest does not say
  std::size_t cases = 0;      // in the whole sweep
  std::size_t shard = 0, shards = 1;
  bool complete = false;
  std::size_t rows = 0, failed = 0;
  std::string scene, origin;
  RowFormat format = RowFormat::csv;
  std::optional<std::size_t> inputs;  // varied-input columns (absent in manifests before issue 18)
};

/// The longest row --resume and merge read back (256 MiB: a row of 10^5 inputs and series
/// elements is a few MiB). Rows files are read a line at a time, so their size is not limited.
inline constexpr std::size_t max_row_bytes = std::size_t{256} << 20;

/// Throws UsageError when `m`, the manifest of `file`, records rows of another rows_format than
/// this mechgraph writes: which program wrote them, what differs, and `remedy` (what to do). A
/// manifest that records none passes: its rows are checked as they are (unrecorded_format_note).
void require_rows_format(const SweepManifest& m, const std::string& file, const std::string& remedy);

/// What a refusal of the rows of `m` adds when their manifest does not record their format (the
/// rows may be another mechgraph's, written otherwise); empty when it does.
std::string unrecorded_format_note(const SweepManifest& m);

/// Reads FILE.json beside `file`; throws UsageError naming it when absent, unreadable, larger than
/// 64 KiB, not a regular file or out of range (more than max_sweep_cases, a shard outside 0 <= I < N
/// <= 10^6, more rows than cases).
SweepManifest read_manifest_checked(const std::filesystem::path& file);

/// Whether FILE.json beside `file` is a sweep manifest: the proof --force needs that mechgraph wrote FILE.
bool has_sweep_manifest(const std::filesystem::path& file);

/// Writes FILE.json beside `file` whole; a manifest path holding anything but an earlier manifest is refused.
void write_manifest(const std::filesystem::path& file, const SweepManifest& manifest);

/// Same as read_manifest_checked.
SweepManifest read_manifest(const std::filesystem::path& file);
std::filesystem::path manifest_path(const std::filesystem::path& file);

class SweepFile {
 public:
  /// Opens `out` (or stdout when empty). An existing FILE (or FILE.part without `resume`) is
  /// refused unless `force`, and even then unless mechgraph wrote it. With `resume`, `rules`
  /// check every row carried over.
  SweepFile(const std::filesystem::path& out, SweepManifest manifest, bool resume, bool force, const RowRules& rules);
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
  void resume_part(const RowRules& rules);
  void start_fresh(bool resume, bool force);
  std::filesystem::path out_, part_;
  SweepManifest manifest_;
  std::optional<OutputLock> lock_;
  FileHandle file_;
  std::vector<std::string> resumed_header_;
  std::vector<std::size_t> resumed_cases_;
  std::size_t resumed_failed_ = 0;
};

}  // namespace mechgraph::cli
