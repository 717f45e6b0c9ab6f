#pragma once
// The plugin ABI version. Bump it whenever a public header under core/include changes in a way
// that breaks binary compatibility of plugins. CMake reads the number from the line below.
#define MECHGRAPH_PLUGIN_ABI_VERSION 1
