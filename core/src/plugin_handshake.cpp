#include "plugin_handshake.hpp"

#include "c_node_type.hpp"
#include "c_plugin_host.hpp"

#include <mechgraph/scene.hpp>
#include <mechgraph/semantic_version.hpp>

#include <algorithm>
#include <charconv>
#include <cstddef>
#include <map>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

namespace mechgraph::detail {
namespace {

// "abi4;gcc-12;cxx202002;glibcxx-abi1" -> {"abi": "4", "compiler": "gcc-12", "cxx": "202002", ...}
std::map<std::string, std::string> fingerprint_fields(const std::string& fingerprint) {
  std::map<std::string, std::string> out;
  std::stringstream ss(fingerprint);
  for (std::string item; std::getline(ss, item, ';');) {
    if (item.rfind("abi", 0) == 0) out["abi"] = item.substr(3);
    else if (item.rfind("cxx", 0) == 0) out["cxx"] = item.substr(3);
    else if (item.rfind("glibcxx-abi", 0) == 0) out["glibcxx-abi"] = item.substr(11);
    else out["compiler"] = item;
  }
  return out;
}

// Names each field of the build fingerprint that differs and what to rebuild with.
std::string explain_fingerprint_mismatch(const std::string& plugin, const std::string& host) {
  const auto p = fingerprint_fields(plugin);
  const auto h = fingerprint_fields(host);
  auto field = [](const std::map<std::string, std::string>& m, const char* key) {
    const auto it = m.find(key);
    return it == m.end() ? std::string("unknown") : it->second;
  };
  std::vector<std::string> differences;
  if (field(p, "compiler") != field(h, "compiler"))
    differences.push_back("compiler: plugin " + field(p, "compiler") + ", mechgraph " + field(h, "compiler") +
                          " (build the plugin with the compiler that built mechgraph: CMAKE_CXX_COMPILER)");
  if (field(p, "cxx") != field(h, "cxx"))
    differences.push_back("C++ standard: plugin " + cxx_standard_name(field(p, "cxx")) + ", mechgraph " +
                          cxx_standard_name(field(h, "cxx")) + " (rebuild the plugin with " +
                          (h.count("cxx") && h.at("cxx").substr(0, 6) == "202002" ? "-std=c++20" : "mechgraph's standard") +
                          "; mechgraph_add_plugin() sets it unless a -std= compile option overrides it)");
  if (field(p, "glibcxx-abi") != field(h, "glibcxx-abi"))
    differences.push_back("libstdc++ string ABI: plugin _GLIBCXX_USE_CXX11_ABI=" + field(p, "glibcxx-abi") +
                          ", mechgraph " + field(h, "glibcxx-abi") + " (do not set _GLIBCXX_USE_CXX11_ABI)");
  if (field(p, "abi") != field(h, "abi"))
    differences.push_back("plugin ABI: plugin " + field(p, "abi") + ", mechgraph " + field(h, "abi"));
  std::string out = "was built with a toolchain this mechgraph cannot share C++ objects with (plugin '" + plugin +
                    "', mechgraph '" + host + "'); what differs:";
  for (const std::string& d : differences) out += "\n    " + d;
  if (differences.empty()) out += " the fingerprints' text; rebuild the plugin with the same toolchain";
  return out;
}

}  // namespace

// A standard's value is given before the standard is published, and differently by each compiler
// (C++23: gcc 12 gives 202100, clang 14 202101, the standard 202302): each standard names the
// values after its predecessor's, up to its own.
std::string cxx_standard_name(const std::string& cplusplus) {
  const char* const last_char = cplusplus.data() + cplusplus.size();
  long value = 0;
  const auto [end, error] = std::from_chars(cplusplus.data(), last_char, value);
  const bool whole = end == last_char || (*end == 'L' && end + 1 == last_char);
  if (error != std::errc() || !whole || value < 199711) return "__cplusplus " + cplusplus;
  static constexpr std::pair<long, const char*> standards[] = {
      {199711, "C++98"}, {201103, "C++11"}, {201402, "C++14"}, {201703, "C++17"}, {202002, "C++20"}, {202302, "C++23"}};
  for (const auto& [last, name] : standards)
    if (value <= last) return std::string(name) + " (__cplusplus " + cplusplus + ")";
  return "a standard after C++23 (__cplusplus " + cplusplus + ")";
}

void throw_plugin_load_failure(const std::string& where, const std::string& reason) {
  if (reason.find("libmechgraph.so") != std::string::npos || reason.find("libmechgraph_sdk.so") != std::string::npos)
    throw PluginError(where + ": cannot be loaded (" + reason + "): it was built against another mechgraph SDK; rebuild it "
                      "against this mechgraph " MECHGRAPH_SDK_VERSION " (find_package(mechgraph CONFIG) of this install)");
  throw PluginError(where + ": cannot be loaded as a shared library (" + reason + ")");
}

const PluginDescriptor& checked_plugin_descriptor(PluginEntry* entry, const std::string& where) {
  const PluginDescriptor* d = call_plugin(where, "its entry", [&] { return entry(); });
  if (!d) throw PluginError(where + ": its entry returned no descriptor");
  if (d->abi_version != plugin_abi_version)
    throw PluginError(where + " was built for plugin ABI version " + std::to_string(d->abi_version) +
                      ", this mechgraph " MECHGRAPH_SDK_VERSION " uses ABI version " + std::to_string(plugin_abi_version) +
                      "; rebuild the plugin against this mechgraph's SDK (find_package(mechgraph " MECHGRAPH_SDK_VERSION
                      " CONFIG) and mechgraph_add_plugin)");
  const std::string id = d->plugin_id ? d->plugin_id : "";
  if (!d->build_fingerprint || std::string(d->build_fingerprint) != build_fingerprint)
    throw PluginError(where + " ('" + id + "') " +
                      explain_fingerprint_mismatch(d->build_fingerprint ? d->build_fingerprint : "", build_fingerprint));
  if (id.empty()) throw PluginError(where + ": its descriptor has an empty plugin id");
  if (!d->make_node_types) throw PluginError(where + ": its descriptor has no node type factory");
  const std::string version = d->plugin_version ? d->plugin_version : "";
  if (!SemanticVersion::parse(version))
    throw PluginError(where + " ('" + id + "'): its version '" + version +
                      "' is not a semantic version MAJOR.MINOR.PATCH (e.g. \"0.1.0\"); fix the MECHGRAPH_PLUGIN line");
  return *d;
}

std::string plugin_where(const std::string& where, const PluginDescriptor& d) {
  return where + " ('" + (d.plugin_id ? d.plugin_id : "") + "')";
}

namespace {

// Port, parameter and effect names become CSV headers, file names and plot titles: they follow the
// grammar of scene names (a port called "../x" or "a,b" is a defect of the plugin). Each type once.
void check_node_type(const NodeInfo& described, const std::string& named, const std::string& where, std::set<std::string>& own) {
  const std::string& name = described.type;
  if (name.empty()) throw PluginError(where + ": a node type has an empty name");
  if (!own.insert(name).second) throw PluginError(where + " provides node type '" + name + "' twice");
  const auto check_name = [&](const std::string& what, const std::string& n) {
    if (const std::string why = name_problem(n); !why.empty())
      throw PluginError(named + ": node type '" + name + "' has a " + what + " whose name " + why);
  };
  for (const PortSpec& port : described.inputs) check_name("input port", port.name);
  for (const PortSpec& port : described.outputs) check_name("output port", port.name);
  for (const EffectSpec& effect : described.effects) check_name("effect", effect.name);
  for (const ParamSpec& param : described.params) {
    check_name("parameter", param.name);
    for (const ParamSpec& field : param.fields) check_name("record field", field.name);
  }
}

}  // namespace

NodeTypeList checked_plugin_node_types(const PluginDescriptor& d, const std::string& where) {
  const std::string named = plugin_where(where, d);
  NodeTypeList types = call_plugin(named, "its node type factory", [&] { return d.make_node_types(); });
  std::set<std::string> own;
  for (const auto& t : types) {
    if (!t) throw PluginError(where + ": returned an empty node type");
    const NodeInfo& described = call_plugin(named, "a node type's info()", [&]() -> const NodeInfo& { return t->info(); });
    check_node_type(described, named, where, own);
  }
  return types;
}

const mg_plugin& checked_c_plugin(mg_plugin_entry_fn* entry, const std::string& where) {
  std::string why;
  mg_text_sink sink{&why, [](void* self, const char* text, size_t size) {
                      auto& out = *static_cast<std::string*>(self);
                      if (text && out.size() < 4000) out.append(text, std::min<size_t>(size, 4000 - out.size()));
                    }};
  const mg_plugin* p = call_plugin(where, "its entry", [&] { return entry(&c_plugin_host(), sink); });
  if (!p)
    throw PluginError(where + ": its entry refused to load" +
                      (why.empty() ? std::string(" without saying why") : ": " + quoted_text_excerpt(why, 400)));
  constexpr std::size_t required = offsetof(mg_plugin, interface_count);
  if (p->struct_size < required)
    throw PluginError(where + ": its mg_plugin is " + std::to_string(p->struct_size) + " bytes (struct_size), shorter than the " +
                      std::to_string(required) + " bytes every SDK 1.x plugin fills; a defect of the plugin");
  const std::string host_sdk = std::to_string(MG_SDK_MAJOR) + "." + std::to_string(MG_SDK_MINOR);
  const std::string plugin_sdk = std::to_string(p->sdk_major) + "." + std::to_string(p->sdk_minor);
  if (p->sdk_major != MG_SDK_MAJOR)
    throw PluginError(where + " was built against mechgraph SDK " + plugin_sdk + ", this mechgraph " MECHGRAPH_SDK_VERSION
                      " provides SDK " + host_sdk + " (another major version: rebuild the plugin against SDK " + host_sdk + ")");
  if (p->sdk_minor > MG_SDK_MINOR)
    throw PluginError(where + " was built against mechgraph SDK " + plugin_sdk + ", newer than SDK " + host_sdk +
                      " of this mechgraph " MECHGRAPH_SDK_VERSION " (it may need what this mechgraph lacks): update "
                      "mechgraph, or rebuild the plugin against SDK " + host_sdk);
  const std::string id = p->plugin_id ? p->plugin_id : "";
  if (id.empty()) throw PluginError(where + ": its mg_plugin has an empty plugin id");
  const std::string version = p->plugin_version ? p->plugin_version : "";
  if (!SemanticVersion::parse(version))
    throw PluginError(where + " ('" + id + "'): its version '" + version +
                      "' is not a semantic version MAJOR.MINOR.PATCH (e.g. \"0.1.0\")");
  if (p->node_type_count > 0 && !p->node_types)
    throw PluginError(plugin_where(where, *p) + ": its node types are a null pointer with a count of " +
                      std::to_string(p->node_type_count));
  return *p;
}

std::string plugin_where(const std::string& where, const mg_plugin& p) {
  return where + " ('" + (p.plugin_id ? p.plugin_id : "") + "')";
}

std::string c_plugin_fingerprint(const mg_plugin& p) {
  return "sdk" + std::to_string(p.sdk_major) + "." + std::to_string(p.sdk_minor) +
         (p.built_with && *p.built_with ? std::string("; ") + p.built_with : std::string());
}

NodeTypeList checked_c_plugin_node_types(const mg_plugin& p, const std::string& where, bool through_c) {
  const std::string named = plugin_where(where, p);
  NodeTypeList types;
  std::set<std::string> own;
  for (std::size_t i = 0; i < p.node_type_count; ++i) {
    if (!p.node_types[i]) throw PluginError(named + ": node type " + std::to_string(i) + " is a null pointer");
    types.push_back(make_c_node_type(*p.node_types[i], named, through_c));
    check_node_type(types.back()->info(), named, where, own);
  }
  return types;
}

}  // namespace mechgraph::detail
