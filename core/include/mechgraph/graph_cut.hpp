#pragma once
// A built graph cut down to one node and what it reads: for code that asks one node a question
// (the knob bench, the limit walk of the tests) and must not pay for the scene's other nodes.
#include <mechgraph/graph.hpp>

#include <cstddef>

namespace mechgraph {

/// Keeps node `node` and its producers (transitively), in dependency order; every other node is no
/// longer needed. A node the scene itself culled is kept too, after its producers. The requested
/// outputs and the reports are dropped: the caller requests what it asks for, then calls
/// mark_wanted_outputs. Until then each kept node keeps the outputs it was wanted for in the whole
/// scene, so producers compute what they computed there. A node index past the graph's nodes is
/// std::out_of_range, the graph unchanged.
void cut_to_producers(Graph& graph, std::size_t node);

}  // namespace mechgraph
