#include "results_folder.hpp"

#include "cli.hpp"
#include "output_file.hpp"

#include <mechgraph/errors.hpp>

#include <sys/file.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <ostream>
#include <string>
#include <unistd.h>

namespace mechgraph::cli {
namespace fs = std::filesystem;
namespace {

// The prefix of every staging folder of `dir`: ".NAME.staging-" (mkdtemp adds six random
// characters), a long NAME shortened (bounded_name) so that the folder's name stays within the
// system's 255 bytes for any DIR that fits itself.
std::string staging_prefix(const fs::path& dir) { return "." + bounded_name(dir.filename().string()) + ".staging-"; }

// Whether a folder holds mechgraph's marker as a regular file (lstat: a symlink named so does not count).
bool has_marker(const fs::path& dir) {
  struct stat st {};
  return ::lstat((dir / results_marker).c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

// Removes staging folders of `dir` that a killed process left. Why the lock, not a pid: a pid is
// reused and says nothing across machines sharing a folder (NFS, a cluster's scratch); an flock
// held on the staging folder's marker while it is written is released by the kernel when its
// holder dies, however it died. So a staging folder is removed only when it is provably ours and
// dead: a real folder (not a symlink) owned by this user, named like ours, holding our marker as
// a regular file, and that marker's lock can be taken. The marker gets its name only after its
// writer holds the lock (make_staging), so a folder being set up is never taken for a dead one.
void remove_stale_staging(const fs::path& dir) {
  const fs::path parent = dir.parent_path().empty() ? fs::path(".") : dir.parent_path();
  const std::string prefix = staging_prefix(dir);
  std::error_code ec;
  for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    struct stat st {};
    if (::lstat(it->path().c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != ::geteuid()) continue;
    const int fd = ::open((it->path() / results_marker).c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) continue;
    FileHandle marker(fd);
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || ::flock(fd, LOCK_EX | LOCK_NB) != 0) continue;  // alive, or not ours
    std::error_code ignored;
    fs::remove_all(it->path(), ignored);
  }
}

// A fresh staging folder beside `dir` with an unpredictable name (mkdtemp), its marker created
// under a temporary name, locked, then renamed to `.mechgraph-results`; the returned handle holds
// the lock until the results are in place.
FileHandle make_staging(const fs::path& dir, fs::path& staging) {
  const fs::path parent = dir.parent_path().empty() ? fs::path(".") : dir.parent_path();
  std::string pattern = (parent / (staging_prefix(dir) + "XXXXXX")).string();
  if (!::mkdtemp(pattern.data())) io_failure("make the staging folder", pattern, errno);
  staging = pattern;
  try {
    // mkdtemp makes it 0700; results are read by others as a folder made by mkdir would be (umask).
    const mode_t mask = ::umask(0);
    ::umask(mask);
    if (::chmod(staging.c_str(), 0777 & ~mask) != 0) io_failure("set the permissions of", staging, errno);
    const fs::path locking = staging / ".mechgraph-results.new";
    const int fd = ::open(locking.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0) io_failure("make the marker in", staging, errno);
    FileHandle marker(fd);
    if (::flock(fd, LOCK_EX) != 0) io_failure("lock the marker in", staging, errno);
    write_all(fd, "written by mechgraph; --force may replace this folder\n", locking);
    if (std::rename(locking.c_str(), (staging / results_marker).c_str()) != 0) io_failure("name the marker in", staging, errno);
    return marker;
  } catch (...) {
    // A staging folder without its marker would never be cleaned up as stale: remove it now.
    std::error_code ignored;
    fs::remove_all(staging, ignored);
    throw;
  }
}

}  // namespace

void check_written(const std::ostream& stream, const fs::path& file) {
  if (!stream) throw IoError("cannot write '" + file.string() + "' (disk full or no permission?)");
}

fs::path results_folder_path(const fs::path& dir) {
  fs::path p = dir.lexically_normal();
  while (!p.has_filename() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
  const std::string name = p.filename().string();
  if (p.empty() || name.empty() || name == "." || name == "..")
    throw UsageError("--out '" + dir.string() + "': name a results folder (its contents are replaced as a whole), e.g. --out results/");
  return p;
}

namespace {

// Whether results can be written beside `dir` at all, asked before the work that makes them (a
// study of hours would otherwise run to its end and lose its results to a read-only or missing
// parent): a folder is made and removed in the nearest existing ancestor of `dir`'s parent, as the
// staging folder will be, so permissions, a read-only file system and a file on the way all show.
void check_writable_beside(const fs::path& dir) {
  fs::path ancestor = dir.parent_path().empty() ? fs::path(".") : dir.parent_path();
  struct stat st {};
  while (::lstat(ancestor.c_str(), &st) != 0) {
    if (errno != ENOENT || !ancestor.has_parent_path() || ancestor.parent_path() == ancestor)
      io_failure("write results into", dir, errno);
    ancestor = ancestor.parent_path().empty() ? fs::path(".") : ancestor.parent_path();
  }
  if (!S_ISDIR(st.st_mode)) io_failure("write results into", dir, ENOTDIR);
  std::string probe = (ancestor / ".mechgraph-probe-XXXXXX").string();  // mkdtemp replaces the six Xs
  if (!::mkdtemp(probe.data())) io_failure("write results into", dir, errno);
  ::rmdir(probe.c_str());
}

}  // namespace

void check_results_folder(const fs::path& given, bool replace) {
  const fs::path dir = results_folder_path(given);
  struct stat st {};
  if (::lstat(dir.c_str(), &st) != 0) {
    if (errno == ENOENT) return check_writable_beside(dir);
    io_failure("write results into", dir, errno);  // e.g. a file on the way: ENOTDIR, exit 5
  }
  if (S_ISLNK(st.st_mode) || !S_ISDIR(st.st_mode))
    throw UsageError("--out " + dir.string() + " is " + kind_of(dir) + ", not a results folder mechgraph wrote: it is left alone " +
                     "(--force replaces only mechgraph's own results); choose another --out");
  std::error_code ec;
  if (fs::is_empty(dir, ec) && !ec) return check_writable_beside(dir);
  if (!replace)
    throw UsageError("the results folder '" + dir.string() + "' exists already: give --force to replace it, or another --out");
  if (!has_marker(dir))
    throw UsageError("--out " + dir.string() + " is a folder mechgraph did not write (no " + results_marker +
                     " in it): it is left alone even with --force; choose another --out or empty it yourself");
  check_writable_beside(dir);
}

void write_results_folder(const fs::path& given, bool replace, const std::function<void(const fs::path& staging)>& write) {
  const fs::path dir = results_folder_path(given);
  check_results_folder(dir, replace);
  std::error_code ec;
  struct stat st {};
  const bool exists = ::lstat(dir.c_str(), &st) == 0;
  const fs::path parent = dir.has_parent_path() ? dir.parent_path() : fs::path(".");
  fs::create_directories(parent, ec);
  if (ec) io_failure("make the folder", parent, ec.value());
  remove_stale_staging(dir);
  fs::path staging;
  FileHandle lock = make_staging(dir, staging);
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

bool is_own_results_folder(const fs::path& given, const fs::path& file) {
  const fs::path dir = results_folder_path(given);
  struct stat st {};
  if (::lstat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) return false;
  return has_marker(dir) && ::lstat((dir / file).c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

}  // namespace mechgraph::cli
