// A plugin that crashes while it is loaded: a static object whose constructor raises SIGSEGV, as a
// broken or hostile library would. The host must survive it (the probe loads it in a child).
#include <mechgraph/plugin_abi.hpp>

#include <csignal>

namespace {

struct CrashOnLoad {
  CrashOnLoad() { std::raise(SIGSEGV); }
};
const CrashOnLoad crash;

mechgraph::NodeTypeList no_types() { return {}; }

}  // namespace

MECHGRAPH_PLUGIN("crash_on_load", "0.0.1", &no_types)
