#pragma once
// Loads plugins, checks their handshake, and holds their node types. Plugins are never unloaded
// while the process runs; each node type and each object a node produces keeps its library
// alive through its deleter, so nothing can outlive the code that destroys it.
#include <mechgraph/node.hpp>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mechgraph {
namespace detail {
class ProbeCache;
}

struct PluginInfo {
  std::string id;
  std::string version;
  std::string fingerprint;
  std::filesystem::path path;
  std::vector<std::string> node_types;
  std::string sdk_version;  // the mechgraph SDK it was compiled against
};

/// A node type as the host sees it: the plugin's object plus what keeps its code loaded.
struct RegisteredType {
  std::shared_ptr<const NodeType> type;
  std::shared_ptr<const void> library;  // the loaded library (opaque for users of this header)
  std::string plugin_id;
  /// The version of the interface each object port carries (docs/design/sdk-1.0.md, 1.7), by the
  /// port's index in info().inputs and info().outputs: what an SDK 1.x type declares
  /// (mg_port_decl::interface_version); for a pre-1.0 C++ type, the version of the SDK interface its
  /// C++ class is bridged as. 0: not an object port, or a private interface without a version.
  std::vector<std::uint32_t> input_interface_versions{}, output_interface_versions{};
  /// False when the type is known to offer no forecast of its own (an SDK 1.x type whose table
  /// answers no mechgraph.node.forecast/1, whichever way the host calls it): the conventions count
  /// it, reading integer parameters, list lengths and input sizes only (work_estimate.hpp). True
  /// for every other type (it may have one).
  bool offers_forecast = true;

  /// The interface version of input (`output` false) or output port `index`, 0 when unknown.
  std::uint32_t interface_version(bool output, std::size_t index) const {
    const auto& versions = output ? output_interface_versions : input_interface_versions;
    return index < versions.size() ? versions[index] : 0;
  }

  /// Wraps an object the plugin produced so that it keeps the plugin's library alive.
  std::shared_ptr<const DomainObject> keep_alive(std::shared_ptr<const DomainObject> object) const;
};

/// A file of a plugin folder that was not loaded, and why.
struct SkippedPlugin {
  std::filesystem::path path;
  std::string reason;
};

/// What a command will use, known before it loads plugins: the node types of a scene and the
/// plugins its `requires:` names.
struct PluginNeeds {
  std::vector<std::string> node_types;
  std::vector<std::string> plugin_ids;
};

class PluginRegistry {
 public:
  /// How long a library stays loaded. `process` (the host's choice): until the process ends, so
  /// no object a plugin made can outlive its code. `objects`: while the registry or any object it
  /// made (node types, their outputs, through keep_alive) holds it; with the last one gone the
  /// library is closed and, unless the loader pins it, unmapped. The loader tests use `objects`
  /// with a plugin built with -fno-gnu-unique, so a lifetime bug shows as a crash, not never.
  enum class Lifetime { process, objects };
  explicit PluginRegistry(Lifetime lifetime = Lifetime::process) : lifetime_(lifetime) {}

  /// Loads one plugin file. Throws PluginError naming the file and the reason: writable by group
  /// or others or owned by another user, not a whole ELF shared library for this machine
  /// (truncated, wrong class or architecture: probed before the dynamic loader maps it), missing
  /// entry, ABI version or build fingerprint mismatch, a node type that another plugin already
  /// provides, a plugin id already loaded.
  void load_file(const std::filesystem::path& file);
  /// Loads every shared library (*.so) in the folder, sorted by name. A file that cannot be loaded
  /// is skipped (see skipped()) and the rest load; a folder writable by group or others is refused
  /// whole (PluginError).
  void load_directory(const std::filesystem::path& folder);
  /// Loads the folders one after another as load_directory does; with `needs`, a file is left
  /// unloaded when the probe cache tells what it provided the last time it was loaded (unchanged
  /// since), and that is none of the needed types and plugins. Every file is loaded, as without
  /// `needs`, when the cache does not know one of them, when two files provided one type or one
  /// plugin id, or when a need is provided by no file; and the rest are loaded after the first
  /// pick when that pick did not provide every need. So a scene finds the same types either way,
  /// and a start loads only what the scene uses. deferred() counts the files left unloaded.
  void load_directories(const std::vector<std::filesystem::path>& folders, const PluginNeeds* needs = nullptr);
  /// Whether the node types of SDK 1.x plugins loaded from now on are all called through the C
  /// boundary. By default (false) a type whose plugin's C++ layer is this host's, byte for byte
  /// (mechgraph.node.cxx/1, sdk/include/mechgraph/c/node_cxx.h), runs as itself, as a type of the
  /// host's own would; every other type runs through C. `mechgraph plugin-test` sets it, so that a
  /// plugin's conformance kit checks the boundary that a host of another compiler or release uses.
  void set_node_types_through_c(bool through_c) { through_c_ = through_c; }
  /// How many plugin files load_directories left unloaded because nothing needed them.
  std::size_t deferred() const { return deferred_; }
  /// The files load_directory skipped, with their reasons.
  const std::vector<SkippedPlugin>& skipped() const { return skipped_; }

  /// The built-in plugin folder, found relative to libmechgraph itself: <libdir>/mechgraph/plugins
  /// beside lib/libmechgraph.so (the same layout in the build tree and after `cmake --install`, so no
  /// build path is baked into the library).
  static std::filesystem::path builtin_plugin_dir();
  /// The plugin folders in order of precedence: `extra` (--plugin-dir, in the order given), then the
  /// folders of MECHGRAPH_PLUGIN_PATH (':'-separated), then builtin_plugin_dir(). With `only`, just
  /// `extra` (--only-plugin-dir). A folder listed twice is kept once. Never ".".
  static std::vector<std::filesystem::path> search_path(const std::vector<std::filesystem::path>& extra, bool only);

  const RegisteredType* find(std::string_view type) const;
  std::vector<std::string> type_names() const;
  const std::vector<PluginInfo>& plugins() const { return plugins_; }
  /// Every effect some loaded node type implements.
  std::vector<std::string> effect_names() const;

 private:
  std::vector<PluginInfo> plugins_;
  std::vector<SkippedPlugin> skipped_;
  std::vector<std::pair<std::string, RegisteredType>> types_;
  std::size_t deferred_ = 0;
  Lifetime lifetime_ = Lifetime::process;
  bool through_c_ = false;
  std::shared_ptr<detail::ProbeCache> probes_;  // the probe cache, read once for all the files loaded
  /// The *.so files of a folder, sorted, as load_directory takes them (a link leading out of the
  /// folder is skipped here).
  std::vector<std::filesystem::path> plugin_files(const std::filesystem::path& folder);
  void load_or_skip(const std::filesystem::path& file);
  /// The files of `files` that provide a need, or nullopt when the cache cannot say (see load_directories).
  std::optional<std::vector<std::filesystem::path>> needed_files(const std::vector<std::filesystem::path>& files,
                                                                 const PluginNeeds& needs);
  bool provides_all(const PluginNeeds& needs) const;
  bool has_plugin(std::string_view id) const;
};

}  // namespace mechgraph
