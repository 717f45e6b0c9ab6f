#pragma once
// Symbol visibility. Plugins are built with hidden visibility (mechgraph_add_plugin sets
// -fvisibility=hidden and -fvisibility-inlines-hidden), so a plugin exports its entry and nothing
// else unless it says so. Two things must stay visible:
//  - MECHGRAPH_INTERFACE on every class whose type crosses a library boundary (node and domain
//    interfaces, error classes): host and plugin then agree on one RTTI, so dynamic_cast of a domain
//    object and catching a NodeError thrown in a plugin work.
//  - MECHGRAPH_EXPORT on the plugin's entry, which MECHGRAPH_PLUGIN declares for you.
#define MECHGRAPH_INTERFACE __attribute__((visibility("default")))
#define MECHGRAPH_EXPORT __attribute__((visibility("default")))
