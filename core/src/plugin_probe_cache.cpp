#include "plugin_probe_cache.hpp"

#include <mechgraph/bounded_read.hpp>
#include <mechgraph/errors.hpp>

#include <spdlog/spdlog.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string_view>
#include <system_error>
#include <unordered_set>

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

// Past this size the next line written first drops the lines of files that changed or are gone:
// every build, upgrade or removed build tree leaves its keys behind, and each start reads the
// whole file (340 KiB of such lines made a one-case sweep's start 18 % slower). A machine's
// current plugins take about 300 bytes each, so the file stays well below it.
constexpr std::size_t probe_cache_prune_size = std::size_t{32} << 10;

// The key a line starts with: the line itself, or what stands before its manifest mark.
std::string_view key_of_line(std::string_view line) {
  const std::size_t mark = line.find('\t');
  return mark == std::string_view::npos ? line : line.substr(0, mark);
}

// The file a key names: all before its last three fields (size, change time, inode), since the
// path may hold spaces. Empty when the key does not have that form.
std::string_view path_of_key(std::string_view key) {
  std::size_t end = key.size();
  for (int field = 0; field < 3; ++field) {
    const std::size_t space = key.rfind(' ', end == 0 ? 0 : end - 1);
    if (space == std::string_view::npos || space == 0) return {};
    end = space;
  }
  return key.substr(0, end);
}

// Writes all of `text` to `fd`, retried on EINTR and short writes; false on any failure.
bool write_all(int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    text.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

// Rewrites the cache with only the lines whose key is still its file's key (the file is there,
// unchanged), each line once: the acceptance line of a key, then its last manifest, the one a
// lookup reads. Written to a new file beside it and renamed over it, so a reader sees the old file
// or the new one, never a part. A line another process appends to the old file meanwhile is lost:
// its file is probed once more. Any failure leaves the old file as it was.
void prune_probe_cache(const std::filesystem::path& cache) {
  std::string text;
  try {
    text = read_bounded_file(cache, probe_cache_limit);
  } catch (const FileReadError&) {
    return;  // too big or unreadable: append_line starts it again
  }
  std::unordered_map<std::string, bool> current;  // key -> whether it is its file's key now
  std::vector<std::string_view> keys;             // in the order first seen
  std::unordered_set<std::string_view> accepted;
  std::unordered_map<std::string_view, std::string_view> manifests;  // key -> its last manifest line
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::string_view line(text.data() + at, end - at);
    at = end + 1;
    const std::string_view key = key_of_line(line);
    const std::string_view path = path_of_key(key);
    if (path.empty()) continue;
    auto [it, fresh] = current.try_emplace(std::string(key), false);
    if (fresh) {
      it->second = probe_key(std::string(path)) == key;
      if (it->second) keys.push_back(key);
    }
    if (!it->second) continue;
    if (key.size() == line.size()) accepted.insert(key);
    else manifests[key] = line;
  }
  std::string kept;
  for (const std::string_view key : keys) {
    if (accepted.count(key)) kept.append(key).push_back('\n');
    if (const auto m = manifests.find(key); m != manifests.end()) kept.append(m->second).push_back('\n');
  }
  if (kept.size() == text.size()) return;  // nothing to drop
  std::string temporary = cache.string() + ".XXXXXX";
  const int fd = ::mkstemp(temporary.data());  // O_EXCL: never a file or link already there
  if (fd < 0) return;
  const bool written = ::fchmod(fd, 0644) == 0 && write_all(fd, kept);
  if (::close(fd) != 0 || !written || std::rename(temporary.c_str(), cache.c_str()) != 0) ::unlink(temporary.c_str());
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
    if (static_cast<std::uintmax_t>(st.st_size) > probe_cache_prune_size) {
      prune_probe_cache(cache);
      if (::lstat(cache.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) return;
    }
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
