// A plugin whose build fingerprint differs (as if built by another compiler): refused.
#include <mechgraph/plugin_abi.hpp>

namespace {
mechgraph::NodeTypeList no_types() { return {}; }
const mechgraph::PluginDescriptor* descriptor() {
  static const mechgraph::PluginDescriptor d{mechgraph::plugin_abi_version, "foreign", "1.0", "abi1;othercc-1;cxx1", &no_types};
  return &d;
}
}  // namespace
BOOST_DLL_ALIAS(descriptor, mechgraph_plugin)
