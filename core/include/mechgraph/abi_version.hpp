#pragma once
// The plugin ABI version. Bump it whenever a public header under core/include changes in a way
// that breaks binary compatibility of plugins. CMake reads the number from the line below.
// 2: table values, effects with their outputs and parameters, ValveMotion and Spring interfaces,
//    CamLaw::higher_derivatives.
// 3: EvalContext::wanted (which outputs are read downstream).
#define MECHGRAPH_PLUGIN_ABI_VERSION 3
