#pragma once
// The plugin handshake. Each plugin exports one C function, `mechgraph_plugin_entry`, declared by
// MECHGRAPH_PLUGIN; it returns a PluginDescriptor. The host reads `abi_version` first (it stays the
// first member forever) and refuses a mismatch before touching anything else, then compares the build
// fingerprint (compiler, C++ standard, standard library ABI), because the node interfaces are C++
// classes. A refused plugin's message names each field that differs and what to rebuild with.
//
// Versions: `plugin_version` is the plugin's own semantic version (MAJOR.MINOR.PATCH); scenes can
// state what they need (`requires: { cams: ">=0.2" }`). `sdk_version` is the mechgraph SDK the plugin
// was compiled against, reported with the plugin (mechgraph plugins).
#include <mechgraph/abi_version.hpp>
#include <mechgraph/export.hpp>
#include <mechgraph/node.hpp>
#include <mechgraph/version.hpp>

#include <cstdint>

namespace mechgraph {

inline constexpr std::uint32_t plugin_abi_version = MECHGRAPH_PLUGIN_ABI_VERSION;
inline constexpr const char* plugin_entry_name = "mechgraph_plugin_entry";
/// The entry of plugins built for ABI 3 and older (a Boost.DLL alias); only recognised to explain a refusal.
inline constexpr const char* legacy_plugin_entry_name = "mechgraph_plugin";

#define MECHGRAPH_STRINGIFY_DETAIL(x) #x
#define MECHGRAPH_STRINGIFY(x) MECHGRAPH_STRINGIFY_DETAIL(x)

/// Identifies the toolchain a plugin was built with; host and plugin must agree field by field:
/// abiN;COMPILER-MAJOR;cxxSTANDARD;glibcxx-abiN.
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
  const char* plugin_version;       // semantic version, "0.1.0"
  const char* build_fingerprint;
  NodeTypeList (*make_node_types)();  // objects are created (and later destroyed) on the plugin's side
  const char* sdk_version;          // MECHGRAPH_SDK_VERSION the plugin was compiled against
};

using PluginEntry = const PluginDescriptor*();

/// This entry hands the host C++ objects, so the plugin must use the host's copy of the SDK's C++
/// layer (libmechgraph_sdk.so.1), not one compiled into it (mechgraph/export.hpp).
#ifdef MECHGRAPH_SDK_CXX_IN_PLUGIN
inline constexpr bool sdk_cxx_shared_with_host = false;
#else
inline constexpr bool sdk_cxx_shared_with_host = true;
#endif

}  // namespace mechgraph

/// Declares the plugin's entry. Use once per plugin, at namespace scope:
///   MECHGRAPH_PLUGIN("cams", "0.1.0", &make_cam_node_types)
#define MECHGRAPH_PLUGIN(id, version, factory)                                                    \
  static_assert(::mechgraph::sdk_cxx_shared_with_host,                                             \
                "MECHGRAPH_PLUGIN, the pre-1.0 entry, shares C++ classes with the host: build the "  \
                "plugin with mechgraph_add_plugin(NAME PRE_1_0_ENTRY ...), or use MECHGRAPH_PLUGIN_1"); \
  extern "C" MECHGRAPH_EXPORT const ::mechgraph::PluginDescriptor* mechgraph_plugin_entry() {      \
    static const ::mechgraph::PluginDescriptor d{::mechgraph::plugin_abi_version, id, version,     \
                                                 ::mechgraph::build_fingerprint, factory,          \
                                                 MECHGRAPH_SDK_VERSION};                           \
    return &d;                                                                                     \
  }
