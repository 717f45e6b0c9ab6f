#include "plugin_probe_cache.hpp"

#include <mechgraph/bounded_read.hpp>
#include <mechgraph/errors.hpp>

#include <spdlog/spdlog.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
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

// Between a key and the manifest written after it: a tab, which no key ends with.
constexpr const char* manifest_mark = "\tprovides ";

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
  append_line(key);
}

std::optional<PluginManifest> ProbeCache::manifest(const std::string& key) {
  if (key.empty() || key.find('\n') != std::string::npos) return std::nullopt;
  const std::lock_guard lock(mutex_);
  if (!manifests_) index_manifests();
  const auto it = manifests_->find(key);
  if (it == manifests_->end()) return std::nullopt;
  PluginManifest m;
  const std::string_view words = it->second;
  for (std::size_t w = 0; w < words.size();) {
    const std::size_t space = std::min(words.find(' ', w), words.size());
    if (space != w) (m.plugin_id.empty() ? m.plugin_id : m.node_types.emplace_back()) = words.substr(w, space - w);
    w = space + 1;
  }
  if (m.plugin_id.empty()) return std::nullopt;
  return m;
}

void ProbeCache::index_manifests() {
  if (!lines_) lines_ = read_probe_cache();
  manifests_.emplace();
  const std::string_view text = *lines_, mark = manifest_mark;
  const std::boyer_moore_horspool_searcher search(mark.begin(), mark.end());
  // One pass over the file for every lookup of this registry. The last line for a key counts.
  for (auto at = text.begin(); at != text.end();) {
    const auto [from, to] = search(at, text.end());
    if (from == text.end()) break;
    const std::size_t line_start = text.rfind('\n', static_cast<std::size_t>(from - text.begin()));
    const std::size_t key_start = line_start == std::string_view::npos ? 0 : line_start + 1;
    const auto end = std::find(to, text.end(), '\n');
    (*manifests_)[std::string(text.substr(key_start, static_cast<std::size_t>(from - text.begin()) - key_start))] =
        std::string(to, end);
    at = end;
  }
}

void ProbeCache::remember_manifest(const std::string& key, const PluginManifest& provided) {
  const auto plain = [](const std::string& name) {
    return !name.empty() && std::none_of(name.begin(), name.end(), [](char c) {
      return static_cast<unsigned char>(c) <= ' ' || c == '\x7f';
    });
  };
  if (key.empty() || key.find('\n') != std::string::npos || !plain(provided.plugin_id) ||
      !std::all_of(provided.node_types.begin(), provided.node_types.end(), plain))
    return;
  std::string words = provided.plugin_id;
  for (const std::string& t : provided.node_types) words += " " + t;
  const std::lock_guard lock(mutex_);
  if (!manifests_) index_manifests();
  std::string& known = (*manifests_)[key];
  if (known == words) return;  // written down already: not once per start
  known = words;
  append_line(key + manifest_mark + words);
}

void ProbeCache::append_line(const std::string& line) {
  if (lines_) lines_->append("\n" + line + "\n");
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
  const std::string whole = line + "\n";
  // One short append: whole lines even with several writers.
  if (::fstat(fd, &opened) == 0 && S_ISREG(opened.st_mode)) (void)!::write(fd, whole.data(), whole.size());
  ::close(fd);
}

}  // namespace mechgraph::detail
