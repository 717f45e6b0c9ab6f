#pragma once
// The probe's cache (GStreamer's registry cache is the model): the plugin files a probe child
// accepted before, so that a process start does not fork once per plugin every time. One file,
// $XDG_CACHE_HOME/mechgraph/plugin-probes (else ~/.cache/mechgraph/plugin-probes), one line per
// accepted file: its absolute path, size, change time and inode. A file that changes is probed
// again. Private to libmechgraph.
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>

namespace mechgraph::detail {

/// The key a file is remembered by (path, size, change time, inode), or "" when it cannot be
/// stat'ed (such a file is never taken from the cache).
std::string probe_key(const std::filesystem::path& file);

/// The cache as one registry sees it: the file is read once, when the first plugin is looked up
/// (a folder of plugins costs one read, not one per plugin), and what this registry accepts is
/// appended to the file and remembered. Lines other processes append later are not seen: such a
/// file is probed once more, never loaded unprobed. Copies of a registry share it: it is locked.
class ProbeCache {
 public:
  /// Whether a file with this key was accepted before.
  bool accepted_before(const std::string& key);
  /// Appends the key of a file the probe accepted.
  void remember(const std::string& key);

 private:
  std::mutex mutex_;
  std::optional<std::string> lines_;  // the file's lines, read on first use, and the keys remembered since
};

}  // namespace mechgraph::detail
