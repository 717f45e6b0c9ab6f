#pragma once
// Reads a file a line at a time through a fixed buffer, so that a reader of many large files
// (merge) holds one line of each, never a whole file. The file must be a regular file (opened
// O_NONBLOCK|O_NOCTTY: a FIFO or a device named here is refused, not waited on); a line longer
// than the limit is refused naming FILE:line. Every failure is a UsageError (not a rows file) or
// an IoError (the system could not read it).
#include "output_file.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace mechgraph::cli {

class LineReader {
 public:
  /// What a last line without a line break is: refused (a finished rows file ends with one), or
  /// kept apart for the caller (a rows file a kill cut: unterminated()).
  enum class LastLine { refuse, keep };
  /// Opens `path`; `max_line` bytes at most per line (the line break not counted).
  LineReader(std::filesystem::path path, std::size_t max_line, LastLine last = LastLine::refuse,
             std::size_t buffer_bytes = std::size_t{1} << 14);
  /// Reads an open regular file from its start (pread: the descriptor's offset is not moved).
  LineReader(int fd, std::filesystem::path path, std::size_t max_line, LastLine last = LastLine::refuse,
             std::size_t buffer_bytes = std::size_t{1} << 14);
  /// The next line, without its '\n', into `line`; false at the end.
  bool next(std::string& line);
  /// LastLine::keep, after next() gave false: the text after the last line break ("" if none),
  /// and the bytes before it (the whole lines).
  const std::string& unterminated() const { return tail_; }
  std::uint64_t whole_bytes() const { return whole_; }
  /// The 1-based number of the line `next` gave last.
  std::size_t number() const { return number_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  bool fill();
  std::filesystem::path path_;
  std::size_t max_line_;
  LastLine last_;
  FileHandle owned_;
  int fd_ = -1;
  std::uint64_t read_ = 0, whole_ = 0;
  std::string tail_;
  std::string buffer_;
  std::size_t begin_ = 0, end_ = 0;
  std::size_t number_ = 0;
  bool eof_ = false;
};

}  // namespace mechgraph::cli
