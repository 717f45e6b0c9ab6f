#include <mechgraph/graph_cut.hpp>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mechgraph {

void cut_to_producers(Graph& graph, std::size_t node) {
  if (node >= graph.nodes.size())
    throw std::out_of_range("cut_to_producers: node " + std::to_string(node) + " of a graph of " +
                            std::to_string(graph.nodes.size()) + " nodes");
  std::vector<bool> keep(graph.nodes.size(), false);
  std::vector<std::size_t> stack{node};
  while (!stack.empty()) {
    const std::size_t i = stack.back();
    stack.pop_back();
    if (keep[i]) continue;
    keep[i] = true;
    for (std::size_t u : graph.nodes[i].upstream) stack.push_back(u);
  }
  // The scene's order, restricted: producers still come before their consumers.
  std::vector<bool> placed(graph.nodes.size(), false);
  std::vector<std::size_t> order;
  for (std::size_t i : graph.order)
    if (keep[i]) {
      order.push_back(i);
      placed[i] = true;
    }
  // A culled node and its culled producers: depth-first post-order, producers first (a needed
  // node's producers are all needed, so the ones placed above need nothing placed here).
  std::vector<std::pair<std::size_t, std::size_t>> path{{node, 0}};  // node, next upstream to visit
  while (!path.empty()) {
    auto& [i, next] = path.back();
    if (placed[i]) {
      path.pop_back();
      continue;
    }
    if (next < graph.nodes[i].upstream.size()) {
      const std::size_t u = graph.nodes[i].upstream[next++];
      if (!placed[u]) path.emplace_back(u, 0);
      continue;
    }
    placed[i] = true;
    order.push_back(i);
    path.pop_back();
  }
  graph.order = std::move(order);
  for (std::size_t i = 0; i < graph.nodes.size(); ++i) graph.nodes[i].needed = keep[i];
  graph.outputs.clear();
  graph.scene_output_count = 0;
  graph.reports.clear();
}

}  // namespace mechgraph
