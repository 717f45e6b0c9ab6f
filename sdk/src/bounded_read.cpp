#include <mechgraph/bounded_read.hpp>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace mechgraph {

BoundedReadError::~BoundedReadError() = default;

namespace {

// Closes the descriptor on every path out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

std::string size_words(std::size_t bytes) {
  if (bytes >= (1u << 20) && bytes % (1u << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

}  // namespace

std::string read_bounded(const std::filesystem::path& file, std::size_t max_bytes) {
  // O_NONBLOCK: opening a FIFO with no writer returns at once instead of waiting forever.
  const Descriptor d{::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
  if (d.fd < 0) throw BoundedReadError(std::string("cannot be opened: ") + std::strerror(errno));
  struct stat st {};
  if (::fstat(d.fd, &st) != 0) throw BoundedReadError(std::string("cannot be examined: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw BoundedReadError("is a folder, not a file");
  if (!S_ISREG(st.st_mode)) throw BoundedReadError("is not a regular file (a device, a FIFO or a socket is refused)");
  if (static_cast<std::size_t>(st.st_size) > max_bytes)
    throw BoundedReadError("is " + size_words(static_cast<std::size_t>(st.st_size)) + ", more than the limit of " +
                           size_words(max_bytes));
  // Read to the end, but never past the limit (a file that grows while we read is cut off there).
  std::string text(static_cast<std::size_t>(st.st_size), '\0');
  std::size_t have = 0;
  for (;;) {
    if (have == text.size()) {
      if (text.size() > max_bytes) throw BoundedReadError("grew past the limit of " + size_words(max_bytes) + " while read");
      text.resize(std::min(max_bytes + 1, std::max<std::size_t>(2 * text.size(), 4096)));
    }
    const ssize_t n = ::read(d.fd, text.data() + have, text.size() - have);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw BoundedReadError(std::string("cannot be read: ") + std::strerror(errno));
    if (n == 0) break;
    have += static_cast<std::size_t>(n);
  }
  if (have > max_bytes) throw BoundedReadError("grew past the limit of " + size_words(max_bytes) + " while read");
  text.resize(have);
  return text;
}

}  // namespace mechgraph
