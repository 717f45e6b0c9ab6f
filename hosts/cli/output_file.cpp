#include "output_file.hpp"

#include "cli.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/hash.hpp>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <streambuf>

namespace mechgraph::cli {
namespace fs = std::filesystem;
void io_failure(const std::string& what, const fs::path& path, int error) {
  throw IoError("cannot " + what + " '" + path.string() + "': " + std::strerror(error));
}

namespace {

// Twelve characters no one can guess (getrandom), so a temporary's name cannot be planted first.
std::string random_suffix() {
  static const char alphabet[] = "abcdefghijklmnopqrstuvwxyz0123456789";
  unsigned char bytes[12];
  std::size_t got = 0;
  while (got < sizeof bytes) {
    const ssize_t n = ::getrandom(bytes + got, sizeof bytes - got, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) io_failure("draw a random name for a temporary file", ".", errno);
    got += static_cast<std::size_t>(n);
  }
  std::string out;
  for (unsigned char b : bytes) out += alphabet[b % (sizeof alphabet - 1)];
  return out;
}

// A stream buffer over a descriptor that remembers the first failure (errno) instead of throwing
// through std::ostream, which would swallow it; write_file_whole checks it after the writer ran.
class FdBuffer final : public std::streambuf {
 public:
  explicit FdBuffer(int fd) : fd_(fd) { setp(buffer_, buffer_ + sizeof buffer_); }
  int error() const { return error_; }
  bool drain() { return flush_buffer(); }

 protected:
  int_type overflow(int_type c) override {
    if (!flush_buffer()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return flush_buffer() ? 0 : -1; }

 private:
  bool flush_buffer() {
    const char* p = pbase();
    while (p < pptr() && !error_) {
      const ssize_t n = ::write(fd_, p, static_cast<std::size_t>(pptr() - p));
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) error_ = errno;
      else p += n;
    }
    setp(buffer_, buffer_ + sizeof buffer_);
    return !error_;
  }
  int fd_;
  int error_ = 0;
  char buffer_[1 << 16];
};

// What a stat mode is, in words for a refusal.
std::string mode_kind(mode_t mode) {
  if (S_ISREG(mode)) return "a regular file";
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

FileHandle& FileHandle::operator=(FileHandle&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.release();
  }
  return *this;
}

FileHandle::~FileHandle() {
  if (fd_ >= 0) ::close(fd_);
}

int FileHandle::release() {
  const int fd = fd_;
  fd_ = -1;
  return fd;
}

std::string kind_of(const fs::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return "absent";
  return mode_kind(st.st_mode);
}

void refuse_unless_ours(const fs::path& path, bool ours, const std::string& what) {
  const std::string kind = kind_of(path);
  if (kind == "absent") return;
  if (kind != "a regular file")
    throw UsageError(what + " " + path.string() + " is " + kind + ", not a file mechgraph wrote: it is left alone (--force " +
                     "replaces only mechgraph's own results); choose another name");
  if (!ours)
    throw UsageError(what + " " + path.string() + " exists and mechgraph did not write it (no manifest says so): it is left " +
                     "alone even with --force; remove it yourself or choose another name");
}

void write_all(int fd, std::string_view text, const fs::path& path) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) io_failure("write", path, errno);
    text.remove_prefix(static_cast<std::size_t>(n));
  }
}

FileHandle create_exclusive(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) {
    if (errno == EEXIST)
      throw UsageError(path.string() + " is in the way (" + kind_of(path) + " already there); it is left alone: remove it yourself");
    io_failure("create", path, errno);
  }
  return FileHandle(fd);
}

FileHandle open_existing_regular(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ELOOP) throw UsageError(path.string() + " is a symbolic link, not the rows mechgraph wrote: it is left alone");
    io_failure("open", path, errno);
  }
  FileHandle handle(fd);
  struct stat st {};
  if (::fstat(fd, &st) != 0) io_failure("inspect", path, errno);
  if (!S_ISREG(st.st_mode)) throw UsageError(path.string() + " is " + mode_kind(st.st_mode) + ", not the rows mechgraph wrote: it is left alone");
  if (st.st_uid != ::geteuid()) throw UsageError(path.string() + " belongs to another user: it is left alone");
  // Back to blocking writes for the rows to come.
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags < 0 || ::fcntl(fd, F_SETFL, (flags & ~O_NONBLOCK) | O_APPEND) != 0) io_failure("open", path, errno);
  return handle;
}

void write_file_whole(const fs::path& target, bool replace, const std::function<void(std::ostream&)>& write) {
  const std::string kind = kind_of(target);
  if (kind != "absent" && !replace) throw UsageError(target.string() + " exists; use --force to replace it");
  if (kind != "absent" && kind != "a regular file")
    throw UsageError(target.string() + " is " + kind + ", not a file mechgraph wrote: it is left alone; choose another name");
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  fs::path temporary;
  int fd = -1;
  for (int attempt = 0; fd < 0; ++attempt) {
    temporary = folder / ("." + bounded_name(target.filename().string()) + ".tmp-" + random_suffix());
    fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0 && (errno != EEXIST || attempt > 100)) io_failure("create a temporary file", temporary, errno);
  }
  FileHandle handle(fd);
  auto discard = [&] {
    std::error_code ignored;
    fs::remove(temporary, ignored);
  };
  try {
    FdBuffer buffer(fd);
    std::ostream os(&buffer);
    write(os);
    os.flush();
    if (!buffer.drain() || buffer.error()) io_failure("write", target, buffer.error() ? buffer.error() : EIO);
    if (!os) io_failure("write", target, EIO);
    if (::fsync(fd) != 0) io_failure("write", target, errno);
    if (::close(handle.release()) != 0) io_failure("write", target, errno);
    if (std::rename(temporary.c_str(), target.c_str()) != 0) io_failure("put in place", target, errno);
  } catch (...) {
    discard();
    throw;
  }
}

std::string bounded_name(const std::string& name) {
  if (name.size() <= 160) return name;
  char hex[20];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(Hasher().add(name).value()));
  return name.substr(0, 96) + "~" + hex;
}

void prepare_output_file(const fs::path& path, const std::string& option) {
  const std::string text = path.string();
  const std::string name = path.filename().string();
  if (text.empty() || text.back() == '/' || name.empty() || name == "." || name == "..")
    throw UsageError(option + " '" + text + "': name a file (e.g. " + option + " rows.csv), not a folder");
  if (name.size() > 250)
    throw UsageError(option + ": the file name is " + std::to_string(name.size()) + " bytes; at most 250 (FILE.part, FILE.lock and " +
                     "FILE.json beside it must fit the system's limit of 255)");
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    throw UsageError(option + " " + text + " is a folder: name a file in it (e.g. " + option + " " + (path / "rows.csv").string() +
                     "); the folder is left alone");
  if (!path.has_parent_path()) return;
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec) io_failure("make the folder", path.parent_path(), ec.value());
}

fs::path OutputLock::lock_path(const fs::path& target) { return fs::path(target.string() + ".lock"); }

OutputLock::OutputLock(const fs::path& target) {
  const fs::path path = lock_path(target);
  // Made fresh when it can be (O_EXCL); an existing one is taken only when it is what mechgraph
  // leaves there (ours, a pid at most): a user's own FILE.lock (`--out Cargo`) is never truncated.
  int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
  const bool created = fd >= 0;
  if (fd < 0 && errno == EEXIST) fd = ::open(path.c_str(), O_RDWR | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ELOOP) throw UsageError(path.string() + " is a symbolic link, not mechgraph's lock: it is left alone; remove it");
    io_failure("open the lock file", path, errno);
  }
  fd_ = FileHandle(fd);
  struct stat st {};
  if (::fstat(fd, &st) != 0) io_failure("inspect the lock file", path, errno);
  if (!S_ISREG(st.st_mode)) throw UsageError(path.string() + " is " + mode_kind(st.st_mode) + ", not mechgraph's lock file: remove it");
  if (!created) {
    char text[32] = {};
    const ssize_t n = st.st_size < 32 ? ::pread(fd, text, sizeof text - 1, 0) : -1;
    bool pid_only = n >= 0 && st.st_uid == ::geteuid();
    for (ssize_t i = 0; pid_only && i < n; ++i) pid_only = (text[i] >= '0' && text[i] <= '9') || (text[i] == '\n' && i == n - 1);
    if (!pid_only)
      throw UsageError(path.string() + " exists and is not mechgraph's lock file (a process id): it is left alone; choose another --out");
  }
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    if (errno != EWOULDBLOCK) io_failure("lock", path, errno);
    char text[32] = {};
    const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
    std::string pid = n > 0 ? std::string(text, static_cast<std::size_t>(n)) : std::string("unknown");
    while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
    throw UsageError(target.string() + " is being written by another mechgraph (pid " + pid + ", holding " + path.string() +
                     "); wait for it to end or choose another --out");
  }
  // The holder's pid, for the message a second writer gets. Not a lock by itself: flock is.
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size()))
    io_failure("write the lock file", path, errno);
}

}  // namespace mechgraph::cli
