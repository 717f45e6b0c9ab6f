#pragma once
// Symbol visibility. Plugins are built with hidden visibility (mechgraph_add_plugin sets
// -fvisibility=hidden and -fvisibility-inlines-hidden), so a plugin exports its entry and nothing
// else unless it says so.
//  - MECHGRAPH_EXPORT on the plugin's entry, which MECHGRAPH_PLUGIN declares for you.
//  - MECHGRAPH_INTERFACE on every class and function of the SDK's C++ layer whose definition lives
//    in the SDK's sources (sdk/src: the interfaces' key functions, the builders, the numerics):
//     * in libmechgraph_sdk.so.1 and the host, and in a plugin of the pre-1.0 entry
//       (MECHGRAPH_PLUGIN), it is default visibility: host and plugin share one copy and one RTTI,
//       so dynamic_cast of a domain object and catching a NodeError thrown in a plugin work;
//     * in a plugin of the SDK 1.x entry built by mechgraph_add_plugin(), which compiles those
//       sources into the plugin with the plugin's own compiler (the target mechgraph::sdk_cxx,
//       which defines MECHGRAPH_SDK_CXX_IN_PLUGIN), it is hidden: the plugin keeps its copy and its
//       RTTI to itself, only C crosses, and any compiler and C++ standard library will do.
#ifdef MECHGRAPH_SDK_CXX_IN_PLUGIN
#define MECHGRAPH_INTERFACE __attribute__((visibility("hidden")))
#else
#define MECHGRAPH_INTERFACE __attribute__((visibility("default")))
#endif
#define MECHGRAPH_EXPORT __attribute__((visibility("default")))
