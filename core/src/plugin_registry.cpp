#include <mechgraph/plugin_registry.hpp>

#include "c_node_type.hpp"
#include "plugin_file_checks.hpp"
#include "plugin_handshake.hpp"
#include "plugin_probe.hpp"

#include <mechgraph/plugin_abi.hpp>

#include <boost/dll/runtime_symbol_info.hpp>
#include <boost/dll/shared_library.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdlib>
#include <set>
#include <sstream>

namespace mechgraph {
namespace {

using Library = boost::dll::shared_library;

// Libraries are kept for the whole process: plugins are never unloaded (docs/writing-plugins.md).
// The list is leaked on purpose so no static destructor can unload a library before objects it
// created are gone.
std::vector<std::shared_ptr<Library>>& all_libraries() {
  static auto* libraries = new std::vector<std::shared_ptr<Library>>();
  return *libraries;
}

template <class T>
std::shared_ptr<const T> tie_to_library(std::shared_ptr<const T> object, std::shared_ptr<const void> library) {
  // Members are destroyed in reverse order: the object first, then the library handle.
  struct Holder {
    std::shared_ptr<const void> library;
    std::shared_ptr<const T> object;
  };
  auto holder = std::make_shared<Holder>(Holder{std::move(library), object});
  return std::shared_ptr<const T>(holder, object.get());
}

}  // namespace

std::shared_ptr<const DomainObject> RegisteredType::keep_alive(std::shared_ptr<const DomainObject> object) const {
  if (!object || !library) return object;
  return tie_to_library(std::move(object), library);
}

void PluginRegistry::load_file(const std::filesystem::path& given) {
  // One absolute, canonical name for the checks, the probe, its cache and the loader: dlopen("x.so")
  // without a slash searches the library path, not the folder the name was given in, so a
  // relative name would probe one file (or none) and load another.
  std::error_code ec_path;
  const std::filesystem::path file = std::filesystem::canonical(given, ec_path);
  if (ec_path || !std::filesystem::is_regular_file(file, ec_path))
    throw PluginError("plugin '" + given.string() + "': no such file");
  const std::string where = "plugin '" + file.string() + "'";
  // Before any code of the file runs, even in the probe's child: who wrote it, that it is a whole
  // library for this machine, and that it declares itself a mechgraph plugin. A library that is not
  // one (a system library a link points at, a file that runs a command when it is loaded) is never
  // mapped.
  detail::check_plugin_ownership(file, where, false);
  detail::check_plugin_elf(file, where);
  // An SDK 1.x plugin exports mechgraph_plugin_entry_1 (the C boundary); a pre-1.0 one the C++ entry.
  const std::vector<bool> entries =
      detail::plugin_exports_symbols(file, {MG_PLUGIN_ENTRY, plugin_entry_name, legacy_plugin_entry_name}, where);
  const bool sdk1 = entries[0], cxx_entry = entries[1], legacy_entry = entries[2];
  if (!sdk1 && !cxx_entry) {
    if (legacy_entry)
      throw PluginError(where + ": was built for mechgraph plugin ABI 3 or older (its entry is the old '" +
                        std::string(legacy_plugin_entry_name) + "' alias); this mechgraph " MECHGRAPH_SDK_VERSION
                        " uses ABI version " + std::to_string(plugin_abi_version) +
                        "; rebuild the plugin against this mechgraph's SDK (find_package(mechgraph " MECHGRAPH_SDK_VERSION
                        " CONFIG) and mechgraph_add_plugin)");
    throw PluginError(where + ": has no entry '" + std::string(plugin_entry_name) +
                      "'; it is not a mechgraph plugin (a plugin declares one with MECHGRAPH_PLUGIN)");
  }
  // The child loads it and runs the whole handshake; only a file it accepted is loaded here.
  if (!probes_) probes_ = std::make_shared<detail::ProbeCache>();
  detail::probe_plugin_in_child(file, where, *probes_);
  auto library = std::make_shared<Library>();
  boost::dll::fs::error_code ec;
  library->load(boost::dll::fs::path(file.string()), boost::dll::load_mode::rtld_now | boost::dll::load_mode::rtld_local, ec);
  if (ec || !library->is_loaded()) detail::throw_plugin_load_failure(where, ec.message());
  const char* entry_name = sdk1 ? MG_PLUGIN_ENTRY : plugin_entry_name;
  if (!library->has(entry_name))
    throw PluginError(where + ": has no entry '" + std::string(entry_name) +
                      "'; it is not a mechgraph plugin (a plugin declares one with MECHGRAPH_PLUGIN)");
  // From here on the plugin's code runs in this process: it stays mapped even when it is refused
  // (an object it threw, a static it registered, may still point into it).
  if (lifetime_ == Lifetime::process) all_libraries().push_back(library);
  // Both paths end in the same PluginInfo and node types behind the one NodeType interface.
  PluginInfo info;
  NodeTypeList types;
  std::vector<char> offers_forecast;  // by type, for an SDK 1.x plugin: its table's answer
  std::string named;
  const auto refuse_loaded_id = [&](const std::string& id) {
    for (const PluginInfo& p : plugins_)
      if (p.id == id) throw PluginError(where + ": plugin id '" + id + "' is already loaded from '" + p.path.string() + "'");
  };
  if (sdk1) {
    const mg_plugin& p = detail::checked_c_plugin(library->get<mg_plugin_entry_fn>(MG_PLUGIN_ENTRY), where);
    refuse_loaded_id(p.plugin_id);
    // Lifetime::objects: through C, whose series and tables the host copies into its own storage
    // (a C++ type's own would hold code of a library that may be unmapped before them).
    types = detail::checked_c_plugin_node_types(p, where, through_c_ || lifetime_ == Lifetime::objects);
    for (std::size_t i = 0; i < p.node_type_count; ++i) offers_forecast.push_back(detail::c_type_offers_forecast(*p.node_types[i]) ? 1 : 0);
    named = detail::plugin_where(where, p);
    info = PluginInfo{p.plugin_id, p.plugin_version, detail::c_plugin_fingerprint(p), file, {}, p.sdk_version ? p.sdk_version : ""};
  } else {
    const PluginDescriptor& d = detail::checked_plugin_descriptor(library->get<PluginEntry>(plugin_entry_name), where);
    refuse_loaded_id(d.plugin_id);
    types = detail::checked_plugin_node_types(d, where);
    named = detail::plugin_where(where, d);
    info = PluginInfo{d.plugin_id, d.plugin_version, d.build_fingerprint, file, {}, d.sdk_version ? d.sdk_version : ""};
  }
  const std::string id = info.id;
  std::shared_ptr<const void> keep = library;
  std::vector<std::pair<std::string, RegisteredType>> added;
  for (std::size_t k = 0; k < types.size(); ++k) {
    const auto& t = types[k];
    const std::string name = t->info().type;
    if (const RegisteredType* other = find(name)) {
      std::string other_path;
      for (const PluginInfo& p : plugins_)
        if (p.id == other->plugin_id) other_path = p.path.string();
      throw PluginError(named + " provides node type '" + name + "', which plugin '" +
                        other->plugin_id + "' (" + other_path + ") already provides");
    }
    info.node_types.push_back(name);
    detail::PortInterfaceVersions versions = detail::port_interface_versions(*t);
    added.emplace_back(name, RegisteredType{tie_to_library(t, keep), keep, id, std::move(versions.inputs), std::move(versions.outputs),
                                            k >= offers_forecast.size() || offers_forecast[k] != 0});
  }
  const auto as_cxx = static_cast<std::size_t>(
      std::count_if(added.begin(), added.end(), [](const auto& a) { return !detail::runs_through_c(*a.second.type); }));
  for (auto& a : added) types_.push_back(std::move(a));
  spdlog::debug("loaded plugin '{}' {} from {} ({} node types, {} through C, {} called as C++)", id, info.version, file.string(),
                info.node_types.size(), info.node_types.size() - as_cxx, as_cxx);
  plugins_.push_back(std::move(info));
  try {  // a shortcut for later starts: failing to write it down changes nothing here
    probes_->remember_manifest(detail::probe_key(file), detail::PluginManifest{id, plugins_.back().node_types});
  } catch (const std::exception& e) {
    spdlog::debug("plugin probe cache: {} not noted: {}", file.string(), e.what());
  }
}

std::vector<std::filesystem::path> PluginRegistry::plugin_files(const std::filesystem::path& folder) {
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) throw PluginError("plugin folder '" + folder.string() + "' does not exist");
  detail::check_plugin_ownership(folder, "plugin folder '" + folder.string() + "'", true);
  std::vector<std::filesystem::path> files;
  const std::filesystem::path home = std::filesystem::canonical(folder, ec);
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() != ".so" || !entry.is_regular_file()) continue;
    // A link is followed only within its folder (libx.so -> libx.so.1): one that leads elsewhere
    // would load a file from a folder nobody named as a plugin folder (a system library, say).
    if (entry.is_symlink()) {
      const std::filesystem::path target = std::filesystem::canonical(entry.path(), ec);
      if (ec || target.parent_path() != home) {
        const std::string reason = "plugin '" + entry.path().string() + "': a symbolic link to '" +
                                   (ec ? std::string("?") : target.string()) +
                                   "', outside its plugin folder; refused (copy the plugin into the folder, or name "
                                   "the target's folder with --plugin-dir)";
        spdlog::warn("skipped: {}", reason);
        skipped_.push_back({entry.path(), reason});
        continue;
      }
    }
    files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

void PluginRegistry::load_or_skip(const std::filesystem::path& file) {
  try {
    load_file(file);
  } catch (const PluginError& e) {
    spdlog::warn("skipped: {}", e.what());
    skipped_.push_back({file, e.what()});
  }
}

void PluginRegistry::load_directory(const std::filesystem::path& folder) {
  for (const auto& f : plugin_files(folder)) load_or_skip(f);
}

bool PluginRegistry::has_plugin(std::string_view id) const {
  return std::any_of(plugins_.begin(), plugins_.end(), [&](const PluginInfo& p) { return p.id == id; });
}

bool PluginRegistry::provides_all(const PluginNeeds& needs) const {
  return std::all_of(needs.node_types.begin(), needs.node_types.end(), [&](const std::string& t) { return find(t) != nullptr; }) &&
         std::all_of(needs.plugin_ids.begin(), needs.plugin_ids.end(), [&](const std::string& id) { return has_plugin(id); });
}

std::optional<std::vector<std::filesystem::path>> PluginRegistry::needed_files(const std::vector<std::filesystem::path>& files,
                                                                               const PluginNeeds& needs) {
  if (!probes_) probes_ = std::make_shared<detail::ProbeCache>();
  // Who provides what: the plugins loaded already (files given first), then each file's manifest.
  std::set<std::string> ids, types;
  for (const PluginInfo& p : plugins_) ids.insert(p.id);
  for (const auto& [name, t] : types_) types.insert(name);
  std::set<std::string> found_types, found_ids;
  std::vector<std::filesystem::path> picked;
  for (const auto& f : files) {
    std::error_code ec;
    const std::filesystem::path file = std::filesystem::canonical(f, ec);
    if (ec) return std::nullopt;
    const std::optional<detail::PluginManifest> m = probes_->manifest(detail::probe_key(file));
    // Unknown to the cache, or a second claim to an id or a type: load_file decides, as always.
    if (!m) {
      spdlog::debug("loading every plugin: the probe cache does not know what {} provides", file.string());
      return std::nullopt;
    }
    if (!ids.insert(m->plugin_id).second) return std::nullopt;
    bool wanted = std::find(needs.plugin_ids.begin(), needs.plugin_ids.end(), m->plugin_id) != needs.plugin_ids.end();
    if (wanted) found_ids.insert(m->plugin_id);
    for (const std::string& t : m->node_types) {
      if (!types.insert(t).second) return std::nullopt;
      if (std::find(needs.node_types.begin(), needs.node_types.end(), t) != needs.node_types.end()) {
        wanted = true;
        found_types.insert(t);
      }
    }
    if (wanted) picked.push_back(f);
  }
  // Each need is loaded already or claimed by a picked file.
  for (const std::string& t : needs.node_types)
    if (!found_types.count(t) && !find(t)) return std::nullopt;
  for (const std::string& id : needs.plugin_ids)
    if (!found_ids.count(id) && !has_plugin(id)) return std::nullopt;
  return picked;
}

void PluginRegistry::load_directories(const std::vector<std::filesystem::path>& folders, const PluginNeeds* needs) {
  std::vector<std::filesystem::path> files;
  for (const auto& folder : folders)
    for (auto& f : plugin_files(folder)) files.push_back(std::move(f));
  const std::optional<std::vector<std::filesystem::path>> picked = needs ? needed_files(files, *needs) : std::nullopt;
  if (!picked) {
    for (const auto& f : files) load_or_skip(f);
    return;
  }
  for (const auto& f : *picked) load_or_skip(f);
  if (!provides_all(*needs)) {
    // The cache promised more than the files gave (a refusal this time, say): load the rest too.
    spdlog::debug("the plugins picked by the probe cache did not provide every need; loading the others");
    for (const auto& f : files)
      if (std::find(picked->begin(), picked->end(), f) == picked->end()) load_or_skip(f);
    return;
  }
  deferred_ += files.size() - picked->size();
  spdlog::debug("loaded {} plugin files of {}: the others provide nothing this command uses", picked->size(), files.size());
}

std::filesystem::path PluginRegistry::builtin_plugin_dir() {
  boost::dll::fs::error_code ec;
  const auto library = boost::dll::this_line_location(ec);  // this very libmechgraph.so
  if (ec) return {};
  return (std::filesystem::path(library.string()).parent_path() / "mechgraph" / "plugins").lexically_normal();
}

std::vector<std::filesystem::path> PluginRegistry::search_path(const std::vector<std::filesystem::path>& extra, bool only) {
  std::vector<std::filesystem::path> candidates(extra.begin(), extra.end());
  if (!only) {
    if (const char* env = std::getenv("MECHGRAPH_PLUGIN_PATH"); env && *env) {
      std::stringstream ss(env);
      for (std::string item; std::getline(ss, item, ':');)
        if (!item.empty()) candidates.emplace_back(item);
    }
    if (auto builtin = builtin_plugin_dir(); !builtin.empty()) candidates.push_back(builtin);
  }
  std::vector<std::filesystem::path> out;
  std::set<std::filesystem::path> seen;
  for (const auto& folder : candidates) {
    std::error_code ec;
    auto key = std::filesystem::weakly_canonical(folder, ec);
    if (ec) key = folder.lexically_normal();
    if (seen.insert(key).second) out.push_back(folder);
  }
  return out;
}

const RegisteredType* PluginRegistry::find(std::string_view type) const {
  for (const auto& [name, t] : types_)
    if (name == type) return &t;
  return nullptr;
}

std::vector<std::string> PluginRegistry::type_names() const {
  std::vector<std::string> out;
  for (const auto& [name, t] : types_) out.push_back(name);
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::string> PluginRegistry::effect_names() const {
  std::set<std::string> names;
  for (const auto& [name, t] : types_)
    for (const EffectSpec& e : t.type->info().effects) names.insert(e.name);
  return {names.begin(), names.end()};
}

}  // namespace mechgraph
