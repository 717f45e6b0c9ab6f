// A plugin whose version is not a semantic version: refused, since scenes compare versions.
#include <mechgraph/plugin_abi.hpp>

namespace {
mechgraph::NodeTypeList no_types() { return {}; }
}  // namespace
MECHGRAPH_PLUGIN("sloppy", "v2-beta", &no_types)
