#pragma once
// What the host gives an SDK 1.x plugin (sdk/include/mechgraph/c/host.h): the mg_host passed to
// its entry and the suites fetched through it by name and version (mechgraph.log/1,
// mechgraph.eval/1, mechgraph.memory/1). One for the process; immutable. Private to libmechgraph.
#include <mechgraph/c/host.h>

namespace mechgraph::detail {

const mg_host& c_plugin_host();

}  // namespace mechgraph::detail
