#include <mechgraph/bounded_read.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>

namespace mechgraph {

FileReadError::~FileReadError() = default;

namespace {

std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a plain file";
}

std::string size_text(std::size_t bytes) {
  if (bytes >= (std::size_t{1} << 20) && bytes % (std::size_t{1} << 20) == 0)
    return std::to_string(bytes) + " bytes (" + std::to_string(bytes >> 20) + " MiB)";
  return std::to_string(bytes) + " bytes";
}

// Closes the descriptor on every path out.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string read_bounded_file(const std::filesystem::path& path, std::size_t max_bytes) {
  max_bytes = std::min<std::size_t>(max_bytes, std::size_t{1} << 40);  // max_bytes + 1 below never wraps
  const std::string shown = "'" + path.string() + "'";
  Descriptor file;
  // O_NONBLOCK: opening a FIFO for reading does not wait for a writer; O_NOCTTY: a terminal named
  // here does not become ours.
  do file.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  while (file.fd < 0 && errno == EINTR);
  if (file.fd < 0)
    throw FileReadError(FileReadError::Reason::cannot_open, "cannot open " + shown + ": " + std::strerror(errno));
  struct stat st {};
  if (::fstat(file.fd, &st) != 0)
    throw FileReadError(FileReadError::Reason::cannot_open, "cannot examine " + shown + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw FileReadError(FileReadError::Reason::not_regular, shown + " is " + kind_of(st.st_mode) + ", not a regular file");
  if (st.st_size < 0 || static_cast<std::uintmax_t>(st.st_size) > max_bytes)
    throw FileReadError(FileReadError::Reason::too_large, shown + " is " + size_text(static_cast<std::size_t>(st.st_size)) +
                                                              ", more than the limit of " + size_text(max_bytes));
  // A regular file ignores O_NONBLOCK; clear it anyway so a read never returns EAGAIN.
  if (const int flags = ::fcntl(file.fd, F_GETFL); flags >= 0) ::fcntl(file.fd, F_SETFL, flags & ~O_NONBLOCK);
  std::string out;
  out.resize(static_cast<std::size_t>(st.st_size));
  // One read(2) into `to`, retried on EINTR: the bytes it gave, 0 at the end.
  const auto read_some = [&](char* to, std::size_t size) -> std::size_t {
    for (;;) {
      const ssize_t n = ::read(file.fd, to, size);
      if (n >= 0) return static_cast<std::size_t>(n);
      if (errno != EINTR) throw FileReadError(FileReadError::Reason::read_failed, "cannot read " + shown + ": " + std::strerror(errno));
    }
  };
  std::size_t have = 0;
  for (;;) {
    if (have < out.size()) {
      const std::size_t n = read_some(out.data() + have, out.size() - have);
      if (n == 0) break;
      have += n;
      continue;
    }
    // One byte more than the limit allows tells a file that grew past it from one that ends there.
    if (out.size() > max_bytes) break;
    // Full at the size fstat gave, where most files end: their end is asked for in a small buffer,
    // so that finding it never doubles (and copies) the whole file.
    char probe[512];
    const std::size_t n = read_some(probe, sizeof probe);
    if (n == 0) break;
    out.resize(std::min(max_bytes + 1, std::max<std::size_t>(out.size() * 2, 4096)));
    const std::size_t kept = std::min(n, out.size() - have);
    std::memcpy(out.data() + have, probe, kept);
    have += kept;
    if (kept < n) break;  // past the limit: refused below
  }
  if (have > max_bytes)
    throw FileReadError(FileReadError::Reason::too_large,
                        st.st_size == 0 ? shown + " holds more than the limit of " + size_text(max_bytes) +
                                              " (a file that does not tell its size before it is read, as /proc's)"
                                        : shown + " grew past the limit of " + size_text(max_bytes) + " while it was read");
  out.resize(have);
  return out;
}

std::string quoted_text_excerpt(std::string_view text, std::size_t max_chars) {
  static constexpr char hex[] = "0123456789ABCDEF";
  std::string out = "'";
  std::size_t shown = 0;
  for (char ch : text) {
    if (shown == max_chars) {
      out += "...";
      break;
    }
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      out += ch;
    } else {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 0xf];
    }
    ++shown;
  }
  return out + "'";
}

}  // namespace mechgraph
