#pragma once
// Reading a file a user named (a scene, a lift table, a cases file) as hostile input: it must be a
// regular file (not a folder, a FIFO that would block, a device such as /dev/zero that never
// ends). It is opened non-blocking, its type is checked on the opened descriptor (fstat, so a swap
// after the check changes nothing), and at most `max_bytes` are read.
#include <mechgraph/export.hpp>

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace mechgraph {

/// Why a bounded read failed, in words that follow the file's name ("is a folder, not a file").
class MECHGRAPH_INTERFACE BoundedReadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  ~BoundedReadError() override;
};

/// The whole content of `file`; throws BoundedReadError when it cannot be opened, is not a regular
/// file, or is larger than `max_bytes` (the message names the limit).
MECHGRAPH_EXPORT std::string read_bounded(const std::filesystem::path& file, std::size_t max_bytes);

}  // namespace mechgraph
