// The loom plugin's node types (an out-of-tree plugin: tests/out_of_tree/loom/CMakeLists.txt).
#pragma once

#include <mechgraph/node.hpp>

#include <memory>

namespace loom {
std::shared_ptr<const mechgraph::NodeType> make_heddle_law();
std::shared_ptr<const mechgraph::NodeType> make_lever_pivot();
}  // namespace loom
