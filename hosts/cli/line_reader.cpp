#include "line_reader.hpp"

#include "cli.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/sweep/case_table.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace mechgraph::cli {

LineReader::LineReader(int fd, std::filesystem::path path, std::size_t max_line, LastLine last, std::size_t buffer_bytes)
    : path_(std::move(path)), max_line_(max_line), last_(last), fd_(fd), buffer_(buffer_bytes, '\0') {}

LineReader::LineReader(std::filesystem::path path, std::size_t max_line, LastLine last, std::size_t buffer_bytes)
    : path_(std::move(path)), max_line_(max_line), last_(last), buffer_(buffer_bytes, '\0') {
  int fd = -1;
  do fd = ::open(path_.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  while (fd < 0 && errno == EINTR);
  if (fd < 0) {
    if (errno == ENOENT) throw UsageError(path_.string() + ": no such file");
    io_failure("open", path_, errno);
  }
  owned_ = FileHandle(fd);
  fd_ = fd;
  struct stat st {};
  if (::fstat(fd, &st) != 0) io_failure("examine", path_, errno);
  if (!S_ISREG(st.st_mode)) throw UsageError(path_.string() + " is " + kind_of(path_) + ", not a rows file; it is not read");
  if (const int flags = ::fcntl(fd, F_GETFL); flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
}

bool LineReader::fill() {
  if (eof_) return false;
  if (begin_ > 0) {  // keep the unfinished line at the start
    buffer_.erase(0, begin_);
    buffer_.resize(buffer_.size() + begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  if (end_ == buffer_.size()) buffer_.resize(buffer_.size() * 2);  // a line longer than the buffer
  for (;;) {
    const ssize_t n = ::pread(fd_, buffer_.data() + end_, buffer_.size() - end_, static_cast<off_t>(read_));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) io_failure("read", path_, errno);
    if (n == 0) eof_ = true;
    end_ += static_cast<std::size_t>(n);
    read_ += static_cast<std::uint64_t>(n);
    return n > 0;
  }
}

bool LineReader::next(std::string& line) {
  std::size_t scanned = begin_;
  for (;;) {
    const void* found = std::memchr(buffer_.data() + scanned, '\n', end_ - scanned);
    if (found) {
      const std::size_t at = static_cast<std::size_t>(static_cast<const char*>(found) - buffer_.data());
      if (at - begin_ > max_line_) break;
      line.assign(buffer_, begin_, at - begin_);
      whole_ += at + 1 - begin_;
      begin_ = at + 1;
      ++number_;
      return true;
    }
    if (end_ - begin_ > max_line_) break;
    const std::size_t offset = end_ - begin_;
    if (!fill()) {
      if (end_ == begin_) return false;
      if (last_ == LastLine::keep) {
        tail_.assign(buffer_, begin_, end_ - begin_);
        begin_ = end_;
        return false;
      }
      throw UsageError(excerpt(path_.string()) + ":" + std::to_string(number_ + 1) +
                       ": the last line has no line break; not a complete rows file mechgraph wrote");
    }
    scanned = begin_ + offset;
  }
  throw UsageError(excerpt(path_.string()) + ":" + std::to_string(number_ + 1) + ": a line longer than " +
                   std::to_string(max_line_ >> 20) + " MiB; not a rows file mechgraph wrote");
}

}  // namespace mechgraph::cli
