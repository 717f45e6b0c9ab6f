#pragma once
// Writing files the command line produces, so that a hostile folder cannot turn a write into
// something else (issue 18):
//  - whole: a file is written to a temporary made beside it with an unpredictable name
//    (O_CREAT|O_EXCL|O_NOFOLLOW: never an existing file, never through a planted symlink), every
//    write and the close checked, then renamed over the target; a reader sees the old file or the
//    new one, never a part, and a full disk publishes nothing;
//  - checked: every failure is an IoError (exit 5) naming the path and the system's reason;
//  - exclusive: an advisory lock (flock on `FILE.lock`, opened O_NOFOLLOW) keeps two mechgraph
//    processes from writing the same output; the second is refused naming the first's pid;
//  - owned: `--force` replaces a regular file only when the caller knows mechgraph wrote it
//    (`refuse_unless_ours`); devices, FIFOs, symlinks and folders are never replaced.
#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>

namespace mechgraph::cli {

/// Writes `target` whole: `write` fills a stream bound to a fresh temporary in the target's
/// folder (mode 0644 less the umask), which is flushed, checked, closed and renamed over `target`.
/// An existing `target` is refused (UsageError naming --force) unless `replace`; even then only a
/// regular file is replaced (never a symlink, device, FIFO or folder: UsageError). Throws IoError
/// with the path and strerror when a write, the close or the rename fails; the temporary is
/// removed then. An exception from `write` removes the temporary and is rethrown.
void write_file_whole(const std::filesystem::path& target, bool replace, const std::function<void(std::ostream&)>& write);

/// Throws IoError "cannot WHAT 'PATH': <strerror(error)>" (exit 5).
[[noreturn]] void io_failure(const std::string& what, const std::filesystem::path& path, int error);

/// A file descriptor that closes itself.
class FileHandle {
 public:
  FileHandle() = default;
  explicit FileHandle(int fd) : fd_(fd) {}
  FileHandle(FileHandle&& other) noexcept : fd_(other.release()) {}
  FileHandle& operator=(FileHandle&& other) noexcept;
  FileHandle(const FileHandle&) = delete;
  FileHandle& operator=(const FileHandle&) = delete;
  ~FileHandle();
  int get() const { return fd_; }
  int release();
  explicit operator bool() const { return fd_ >= 0; }

 private:
  int fd_ = -1;
};

/// Creates `path` exclusively (O_CREAT|O_EXCL|O_NOFOLLOW|O_CLOEXEC, 0644) for appending; a file,
/// a symlink or anything else already there is refused (UsageError naming it). For the rows file
/// a sweep appends to (FILE.part), whose name --resume must find again.
FileHandle create_exclusive(const std::filesystem::path& path);

/// Opens an existing regular file `path` for reading and writing without following a symlink
/// (O_NOFOLLOW|O_NONBLOCK: a FIFO does not hang the open); anything but a regular file owned by
/// this user is refused (UsageError naming it). For --resume's FILE.part.
FileHandle open_existing_regular(const std::filesystem::path& path);

/// Writes all of `text` to `fd` (retrying short writes and EINTR); IoError naming `path` else.
void write_all(int fd, std::string_view text, const std::filesystem::path& path);

/// What is at `path` without following a symlink: "absent", "a regular file", "a symbolic link",
/// "a folder", "a FIFO", "a device", "a socket".
std::string kind_of(const std::filesystem::path& path);

/// Refuses (UsageError, exit 2) replacing what is at `path` unless it is absent, or a regular file
/// and `ours` (the caller's proof that mechgraph wrote it, e.g. a manifest beside it). `what`
/// names the option ("--out"). The message names the thing and why it is left alone.
void refuse_unless_ours(const std::filesystem::path& path, bool ours, const std::string& what);

/// `name` when it is at most 160 bytes, else its first 96 bytes, '~' and a 16-digit hash of all of
/// it: a name for a temporary or staging entry made from an output's name ("." NAME ".tmp-" and
/// 12 random characters) that stays under the file-name limit of 255 bytes however long the
/// output's name is, and is the same for the same name (stale staging folders are found again).
std::string bounded_name(const std::string& name);

/// Checks that `path` (given as `option`, e.g. "--out") names a file and makes the folders it
/// lies in, as `run --out a/b/DIR` does. Refused (UsageError, exit 2) before anything is created:
/// a path ending in '/', an empty name, ".", "..", a name longer than 250 bytes (FILE.part, FILE.lock
/// and FILE.json must fit the 255-byte limit beside it), or a folder (or a symlink to one) at `path`.
/// Called before the output's lock is taken, so a refused `--out DIR/` leaves no DIR/.lock.
/// IoError (exit 5) when a folder cannot be made.
void prepare_output_file(const std::filesystem::path& path, const std::string& option);

/// An advisory lock on an output: flock(LOCK_EX|LOCK_NB) on `TARGET.lock` beside it (created
/// O_NOFOLLOW, holding the writer's pid). Held until destroyed. A lock held by another process is
/// refused (UsageError) naming that process's pid. The lock file itself is left in place:
/// removing it would let a third process lock a fresh inode while the second still holds the old.
class OutputLock {
 public:
  explicit OutputLock(const std::filesystem::path& target);
  static std::filesystem::path lock_path(const std::filesystem::path& target);

 private:
  FileHandle fd_;
};

}  // namespace mechgraph::cli
