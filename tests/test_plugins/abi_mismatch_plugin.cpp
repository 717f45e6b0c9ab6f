// A plugin built for another plugin ABI version: the host must refuse it, naming both versions.
#include <mechgraph/plugin_abi.hpp>

namespace {
mechgraph::NodeTypeList no_types() { return {}; }
const mechgraph::PluginDescriptor* descriptor() {
  static const mechgraph::PluginDescriptor d{mechgraph::plugin_abi_version + 1, "future", "9.9", mechgraph::build_fingerprint,
                                             &no_types};
  return &d;
}
}  // namespace
BOOST_DLL_ALIAS(descriptor, mechgraph_plugin)
