// A plugin built with another C++ standard than the host (tests/CMakeLists.txt compiles this file
// with C++23): refused with a message that names the standard and what to rebuild with.
#include <mechgraph/plugin_abi.hpp>

namespace {
mechgraph::NodeTypeList no_types() { return {}; }
}  // namespace
MECHGRAPH_PLUGIN("foreign", "1.0.0", &no_types)
