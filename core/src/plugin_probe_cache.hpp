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
#include <unordered_map>
#include <vector>

namespace mechgraph::detail {

/// What a plugin file provided when a process last loaded it: its id and its node types. A registry
/// that knows before loading which types and plugins it needs leaves a file unloaded whose manifest
/// names none of them (GStreamer's registry keeps each plugin's features so, and loads a plugin when
/// one of them is asked for). Written on one line after the key, a tab and "provides".
struct PluginManifest {
  std::string plugin_id;
  std::vector<std::string> node_types;
};

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
  /// What the file with this key provided when it was last loaded, if a process wrote it down.
  std::optional<PluginManifest> manifest(const std::string& key);
  /// Writes down what the file with this key provides, unless that is known already. Nothing is
  /// written for a name holding white space or a control character: such a file is always loaded.
  void remember_manifest(const std::string& key, const PluginManifest& provided);

 private:
  std::mutex mutex_;
  std::optional<std::string> lines_;  // the file's lines, read on first use, and the keys remembered since
  std::optional<std::unordered_map<std::string, std::string>> manifests_;  // key -> "id type type ...", on first use
  void append_line(const std::string& line);  // to lines_ and to the file; mutex_ held
  void index_manifests();                      // fills manifests_ from lines_; mutex_ held
};

}  // namespace mechgraph::detail
