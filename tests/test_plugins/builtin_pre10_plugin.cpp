// The built-in plugins `cams` (BUILTIN_PRE10_CAMS) and `valvetrain` (BUILTIN_PRE10_VALVETRAIN),
// built from their own node types on the pre-1.0 entry (MECHGRAPH_PLUGIN, plugin_abi.hpp), where
// C++ objects cross as they are: the tests that read valvetrain's private objects (a spring
// design) out of a run, and those of the pre-1.0 entry's interplay with SDK 1.x plugins, load
// these in place of the shipped ones (test_support.hpp, builtin_pre10_registry).
#include <mechgraph/plugin_abi.hpp>

#if defined(BUILTIN_PRE10_CAMS)
#include "registration.hpp"
MECHGRAPH_PLUGIN("cams", MECHGRAPH_SDK_VERSION, &mechgraph::cams::node_types)
#elif defined(BUILTIN_PRE10_VALVETRAIN)
#include "node_types.hpp"
MECHGRAPH_PLUGIN("valvetrain", MECHGRAPH_SDK_VERSION, &mechgraph::valvetrain::node_types)
#endif
