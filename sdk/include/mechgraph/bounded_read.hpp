#pragma once
// Reading a file someone else named (a scene's table, a cache) without trusting it: it must be a
// regular file (not a folder, a FIFO that never ends, /dev/zero, a terminal), no larger than a
// limit the caller states, and read with that bound. The file is opened
// O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY (opening a FIFO does not wait for a writer), checked
// with fstat on the open descriptor (no race between the check and the read), then read.
// Error messages name the path and the reason, never the file's contents.
#include <mechgraph/export.hpp>

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace mechgraph {

class MECHGRAPH_INTERFACE FileReadError : public std::runtime_error {
 public:
  enum class Reason { cannot_open, not_regular, too_large, read_failed };
  FileReadError(Reason reason, const std::string& message) : std::runtime_error(message), reason_(reason) {}
  ~FileReadError() override;
  Reason reason() const { return reason_; }

 private:
  Reason reason_;
};

/// 64 MiB: far above any lift table or cache this program reads, far below what would hurt.
inline constexpr std::size_t default_read_limit = std::size_t{64} << 20;

/// The whole contents of the regular file `path`, at most `max_bytes` of it. Throws FileReadError
/// ("'PATH' is a folder/FIFO/device..., not a regular file", "'PATH' is N bytes, more than the limit
/// of M bytes (64 MiB)", "cannot open 'PATH': <strerror>"). A file that grows while it is read
/// past the limit is refused the same way.
MECHGRAPH_INTERFACE std::string read_bounded_file(const std::filesystem::path& path,
                                               std::size_t max_bytes = default_read_limit);

/// Up to `max_chars` characters of `text` for an error message, in single quotes, with control and
/// non-ASCII bytes written as \xNN and "..." where it was cut: an excerpt of untrusted text that
/// cannot flood or garble a terminal.
MECHGRAPH_INTERFACE std::string quoted_text_excerpt(std::string_view text, std::size_t max_chars = 80);

}  // namespace mechgraph
