// The built-in plugins `cams` (BUILTIN_SDK1_CAMS) and `valvetrain` (BUILTIN_SDK1_VALVETRAIN), built
// from their own node types on the SDK 1.x entry (MECHGRAPH_PLUGIN_1) with the shortcut of one C++
// layer off (MECHGRAPH_SDK_CXX_SHORTCUT 0, tests/CMakeLists.txt): every object crosses through its
// C tables, so a test can run the same sweep through C and through the shipped plugins, and compare.
#include <mechgraph/plugin_sdk1.hpp>

#if defined(BUILTIN_SDK1_CAMS)
#include "registration.hpp"
MECHGRAPH_PLUGIN_1("cams", MECHGRAPH_SDK_VERSION, &mechgraph::cams::node_types)
#elif defined(BUILTIN_SDK1_VALVETRAIN)
#include "node_types.hpp"
MECHGRAPH_PLUGIN_1("valvetrain", MECHGRAPH_SDK_VERSION, &mechgraph::valvetrain::node_types)
#endif
