// A plugin built for another plugin ABI version: the host must refuse it, naming both versions.
#include <mechgraph/plugin_abi.hpp>

namespace {
mechgraph::NodeTypeList no_types() { return {}; }
}  // namespace
extern "C" MECHGRAPH_EXPORT const mechgraph::PluginDescriptor* mechgraph_plugin_entry() {
  static const mechgraph::PluginDescriptor d{mechgraph::plugin_abi_version + 1, "future", "9.9.0",
                                             mechgraph::build_fingerprint, &no_types, "9.9.0"};
  return &d;
}
