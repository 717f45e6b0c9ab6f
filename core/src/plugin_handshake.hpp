#pragma once
// The plugin handshake, checked the same way in the probe's child process and in the host: the
// descriptor the entry returns (ABI version, build fingerprint, id, version, factory) and the node
// types its factory makes (present, named, each name once, port and parameter names in the scene
// grammar). Every refusal is a PluginError naming the plugin and what to do. Private to libmechgraph.
#include <mechgraph/bounded_read.hpp>
#include <mechgraph/c/plugin.h>
#include <mechgraph/errors.hpp>
#include <mechgraph/plugin_abi.hpp>

#include <string>

namespace mechgraph::detail {

/// Calls into a plugin (its entry, its node type factory, a type's info()) and turns whatever it
/// throws into a PluginError naming the plugin: a throw of a non-std type must not end the host.
template <class F>
auto call_plugin(const std::string& where, const char* what, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const PluginError&) {
    throw;
  } catch (const std::exception& e) {
    throw PluginError(where + ": " + what + " threw an exception (" + quoted_text_excerpt(e.what(), 200) + "); refused");
  } catch (...) {
    throw PluginError(where + ": " + what + " threw something that is not a std::exception (a defect of the plugin); refused");
  }
}

/// The dynamic loader could not load the file: its own words (`reason`), and what to rebuild when
/// the plugin was built against another libmechgraph.
[[noreturn]] void throw_plugin_load_failure(const std::string& where, const std::string& reason);

/// The language standard a build fingerprint's __cplusplus value ("202002L") names, with the value:
/// "C++20 (__cplusplus 202002L)"; a drafted standard's value names the standard it became.
std::string cxx_standard_name(const std::string& cplusplus);

/// Calls the entry and checks the descriptor it returns; throws PluginError on any mismatch.
const PluginDescriptor& checked_plugin_descriptor(PluginEntry* entry, const std::string& where);

/// "plugin '/path' ('id')": how messages name a plugin once its id is known.
std::string plugin_where(const std::string& where, const PluginDescriptor& d);

/// Calls the node type factory and checks every type it makes; throws PluginError naming the type.
NodeTypeList checked_plugin_node_types(const PluginDescriptor& d, const std::string& where);

// SDK 1.x plugins (entry mechgraph_plugin_entry_1, sdk/include/mechgraph/c/plugin.h).

/// Calls the entry with the host's mg_host and checks the mg_plugin it returns: present (else the
/// plugin's own reason), long enough, sdk_major equal to the host's and sdk_minor not above it
/// (a refusal names both versions), an id and a semantic version.
const mg_plugin& checked_c_plugin(mg_plugin_entry_fn* entry, const std::string& where);

/// "plugin '/path' ('id')" for an SDK 1.x plugin.
std::string plugin_where(const std::string& where, const mg_plugin& p);

/// "sdk1.0; gcc 12.2.0": what `mechgraph plugins` shows in place of a pre-1.0 build fingerprint.
std::string c_plugin_fingerprint(const mg_plugin& p);

/// Wraps every node type of the plugin (c_node_type.hpp) and checks them as the pre-1.0 types are;
/// `through_c` as make_c_node_type's.
NodeTypeList checked_c_plugin_node_types(const mg_plugin& p, const std::string& where, bool through_c);

}  // namespace mechgraph::detail
