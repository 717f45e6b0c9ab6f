#pragma once
// The SDK 1.x entry for C++ node types (docs/design/sdk-1.0.md, section 3.1): the plugin exports
// mechgraph_plugin_entry_1, a C function, and its node types cross to the host as C tables
// (mechgraph/detail/export_node.hpp), so the plugin needs no build fingerprint: any compiler that
// shares the host's C++ standard library ABI will do. Use once per plugin, at namespace scope:
//   MECHGRAPH_PLUGIN_1("myplugin", "1.0.0", &make_node_types)
// Ports that carry domain objects cross too (mechgraph/detail/object_bridge.hpp).
#include <mechgraph/detail/export_node.hpp>

#define MECHGRAPH_PLUGIN_1(id, version, factory)                                                   \
  extern "C" __attribute__((visibility("default"))) const mg_plugin* mechgraph_plugin_entry_1(    \
      const mg_host* host, mg_text_sink why) {                                                     \
    return ::mechgraph::detail::plugin_entry_1(host, why, id, version, factory);                   \
  }
