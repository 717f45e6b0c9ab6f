#pragma once
// The plugin handshake. Each plugin exports one entry, `mechgraph_plugin`, through
// BOOST_DLL_ALIAS; it returns a PluginDescriptor. The host reads `abi_version` first (it stays
// the first member forever) and refuses a mismatch before touching anything else, then compares
// the build fingerprint (compiler, standard library ABI, C++ standard), because the node
// interfaces are C++ classes.
#include <mechgraph/abi_version.hpp>
#include <mechgraph/node.hpp>

#include <boost/dll/alias.hpp>

#include <cstdint>

namespace mechgraph {

inline constexpr std::uint32_t plugin_abi_version = MECHGRAPH_PLUGIN_ABI_VERSION;
inline constexpr const char* plugin_entry_name = "mechgraph_plugin";

#define MECHGRAPH_STRINGIFY_DETAIL(x) #x
#define MECHGRAPH_STRINGIFY(x) MECHGRAPH_STRINGIFY_DETAIL(x)

/// Identifies the toolchain a plugin was built with; host and plugin must agree.
inline constexpr const char* build_fingerprint =
    "abi" MECHGRAPH_STRINGIFY(MECHGRAPH_PLUGIN_ABI_VERSION)
#if defined(__clang__)
    ";clang-" MECHGRAPH_STRINGIFY(__clang_major__)
#elif defined(__GNUC__)
    ";gcc-" MECHGRAPH_STRINGIFY(__GNUC__)
#endif
    ";cxx" MECHGRAPH_STRINGIFY(__cplusplus)
#if defined(_GLIBCXX_USE_CXX11_ABI)
    ";glibcxx-abi" MECHGRAPH_STRINGIFY(_GLIBCXX_USE_CXX11_ABI)
#endif
    ;

struct PluginDescriptor {
  std::uint32_t abi_version;        // must stay first
  const char* plugin_id;            // "cams"
  const char* plugin_version;       // "0.1.0"
  const char* build_fingerprint;
  NodeTypeList (*make_node_types)();  // objects are created (and later destroyed) on the plugin's side
};

using PluginEntry = const PluginDescriptor*();

}  // namespace mechgraph

/// Declares the plugin's entry. Use once per plugin, at namespace scope:
///   MECHGRAPH_PLUGIN("cams", "0.1.0", &make_cam_node_types)
#define MECHGRAPH_PLUGIN(id, version, factory)                                              \
  namespace mechgraph_plugin_entry {                                                        \
  const ::mechgraph::PluginDescriptor* descriptor() {                                       \
    static const ::mechgraph::PluginDescriptor d{::mechgraph::plugin_abi_version, id, version, \
                                                 ::mechgraph::build_fingerprint, factory};  \
    return &d;                                                                              \
  }                                                                                         \
  }                                                                                         \
  BOOST_DLL_ALIAS(mechgraph_plugin_entry::descriptor, mechgraph_plugin)
