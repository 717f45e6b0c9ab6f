#pragma once
// A folder of result files that appears complete or not at all. The files are written into a
// fresh staging folder beside it, which then takes the folder's place in one rename; if the folder
// exists already (and may be replaced), the two are swapped atomically (renameat2 RENAME_EXCHANGE)
// and the old one is removed afterwards. A run killed at any point leaves the old complete
// results or the new complete results, and at worst a stale staging folder, removed by the next
// write of the same folder (see remove_stale_staging in results_folder.cpp).
//
// Ownership (issue 18): every results folder mechgraph writes holds a marker file
// `.mechgraph-results`. `--force` replaces only a real folder (not a symlink to one) that holds
// it, or an empty folder; a folder mechgraph did not make, a file, a symlink, a FIFO or a device
// at DIR is refused (UsageError, exit 2) and left untouched. `--out DIR/` is the same as
// `--out DIR`; `.`, `..` and `/` are refused (a results folder replaces what is at its path).
#include <filesystem>
#include <functional>

namespace mechgraph::cli {

/// The marker file inside every results folder mechgraph writes.
inline constexpr const char* results_marker = ".mechgraph-results";

/// `dir` without trailing separators ("out/" -> "out"); UsageError for ".", "..", "/" or "".
std::filesystem::path results_folder_path(const std::filesystem::path& dir);

/// Refuses (UsageError naming --force) an existing, non-empty `dir` unless `replace`: called before
/// the work, so a run that could not keep its results does not start.
void check_results_folder(const std::filesystem::path& dir, bool replace);

/// Calls `write(staging)` to fill the staging folder, then puts it in place of `dir`. An existing,
/// non-empty `dir` is refused (UsageError naming --force) unless `replace`. Throws IoError with
/// the path and the system's reason when a folder cannot be made, written or renamed.
void write_results_folder(const std::filesystem::path& dir, bool replace,
                          const std::function<void(const std::filesystem::path& staging)>& write);

/// Whether `dir` is a real folder (not a link to one) holding mechgraph's marker and `file` as a
/// regular file: results this program wrote, of the kind `file` names (report.html: a report).
bool is_own_results_folder(const std::filesystem::path& dir, const std::filesystem::path& file);

/// Checks that a stream wrote everything (after closing it); throws IoError naming `file` otherwise.
void check_written(const std::ostream& stream, const std::filesystem::path& file);

}  // namespace mechgraph::cli
