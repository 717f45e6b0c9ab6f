#include "plugin_probe_cache.hpp"

#include <mechgraph/bounded_read.hpp>
#include <mechgraph/errors.hpp>

#include <spdlog/spdlog.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <functional>
#include <string_view>
#include <system_error>

namespace mechgraph::detail {
namespace {

std::filesystem::path probe_cache_file() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "mechgraph" / "plugin-probes";
  if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "mechgraph" / "plugin-probes";
  return {};
}

// The cache is only a shortcut: whatever is wrong with it (a FIFO or a folder in its place, a
// huge or garbled file) costs a probe, never a hang or a crash. Read with a bound, like any file
// this process does not control.
constexpr std::size_t probe_cache_limit = std::size_t{1} << 20;

// The cache file's text; empty when it is missing or cannot be read.
std::string read_probe_cache() {
  const std::filesystem::path cache = probe_cache_file();
  if (cache.empty()) return {};
  try {
    return read_bounded_file(cache, probe_cache_limit);
  } catch (const FileReadError& e) {
    spdlog::debug("plugin probe cache ignored: {}", e.what());
    return {};
  }
}

// Whether `line` is one of the lines of `text`. A key is about 100 characters long, so
// Boyer-Moore-Horspool skips most of the text (one scan costs less than splitting it into lines).
bool has_line(std::string_view text, std::string_view line) {
  const std::boyer_moore_horspool_searcher search(line.begin(), line.end());
  for (auto at = text.begin(); at != text.end();) {
    const auto [from, to] = search(at, text.end());
    if (from == text.end()) return false;
    if ((from == text.begin() || from[-1] == '\n') && (to == text.end() || *to == '\n')) return true;
    at = from + 1;
  }
  return false;
}

}  // namespace

std::string probe_key(const std::filesystem::path& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) return {};
  return file.string() + " " + std::to_string(st.st_size) + " " + std::to_string(st.st_ctim.tv_sec) + "." +
         std::to_string(st.st_ctim.tv_nsec) + " " + std::to_string(st.st_ino);
}

bool ProbeCache::accepted_before(const std::string& key) {
  if (key.empty()) return false;
  const std::lock_guard lock(mutex_);
  if (!lines_) lines_ = read_probe_cache();
  return has_line(*lines_, key);
}

void ProbeCache::remember(const std::string& key) {
  if (key.empty() || key.find('\n') != std::string::npos) return;
  const std::lock_guard lock(mutex_);
  if (lines_) lines_->append("\n" + key + "\n");
  const std::filesystem::path cache = probe_cache_file();
  if (cache.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(cache.parent_path(), ec);
  // Only a regular file (or none) is appended to: a FIFO there would block the open, a device or
  // a folder is not ours to write. Too big: start again.
  struct stat st {};
  if (::lstat(cache.c_str(), &st) == 0) {
    if (!S_ISREG(st.st_mode)) return;
    if (static_cast<std::uintmax_t>(st.st_size) > probe_cache_limit / 2) std::filesystem::remove(cache, ec);
  }
  const int fd = ::open(cache.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC | O_NOCTTY, 0644);
  if (fd < 0) return;
  struct stat opened {};
  const std::string line = key + "\n";
  // One short append: whole lines even with several writers.
  if (::fstat(fd, &opened) == 0 && S_ISREG(opened.st_mode)) (void)!::write(fd, line.data(), line.size());
  ::close(fd);
}

}  // namespace mechgraph::detail
