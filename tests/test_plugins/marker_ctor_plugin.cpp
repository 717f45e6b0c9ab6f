// A library whose static constructor does something when it is loaded, as a hostile one would run
// a command: it appends its process id to the file named by MECHGRAPH_TEST_MARKER. Built twice:
// without an entry (a library that is no plugin: the host must never map it, not even in the probe's
// child), with MARKER_WITH_FOREIGN_ABI, with an entry of another ABI (the probe's child runs it
// and refuses it; the host must then not load it itself), and with MARKER_WITH_ENTRY as a good
// plugin without node types (its marks count the processes that loaded it: the probe's child and
// the host, or the host alone when the probe cache has it).
#include <cstdio>
#include <cstdlib>
#include <unistd.h>

#if defined(MARKER_WITH_FOREIGN_ABI) || defined(MARKER_WITH_ENTRY)
#include <mechgraph/plugin_abi.hpp>
#endif

namespace {

struct MarkOnLoad {
  MarkOnLoad() {
    if (const char* marker = std::getenv("MECHGRAPH_TEST_MARKER"); marker && *marker) {
      if (std::FILE* f = std::fopen(marker, "a")) {
        std::fprintf(f, "%ld\n", static_cast<long>(::getpid()));
        std::fclose(f);
      }
    }
  }
};
const MarkOnLoad mark;

}  // namespace

#if defined(MARKER_WITH_FOREIGN_ABI)
namespace {
mechgraph::NodeTypeList no_types() { return {}; }
}  // namespace
extern "C" MECHGRAPH_EXPORT const mechgraph::PluginDescriptor* mechgraph_plugin_entry() {
  static const mechgraph::PluginDescriptor d{mechgraph::plugin_abi_version + 1, "marker", "1.0.0",
                                             mechgraph::build_fingerprint, &no_types, "9.9.0"};
  return &d;
}
#elif defined(MARKER_WITH_ENTRY)
namespace {
mechgraph::NodeTypeList no_types() { return {}; }
}  // namespace
MECHGRAPH_PLUGIN("marker_good", "1.0.0", &no_types)
#else
extern "C" __attribute__((visibility("default"))) int mechgraph_test_marker_not_a_plugin() { return 7; }
#endif
