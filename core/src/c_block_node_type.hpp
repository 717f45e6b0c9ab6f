#pragma once
// Blocks of cases from a node type of an SDK 1.x plugin (c/node_block.h, mechgraph.node.block/1):
// a C type that answers the interface is offered to sweeps as a BlockEvaluation beside its
// NodeType, so the block path (sweep/block_plan.hpp) and the conformance kit's block check use it
// as they use a pre-1.0 type's blocks. Private to libmechgraph.
#include <mechgraph/c/node.h>
#include <mechgraph/node.hpp>

#include <memory>

namespace mechgraph::detail {

/// `type` (the host's wrapper of `c_type`) with blocks when `c_type` answers
/// mechgraph.node.block/1, else `type` itself.
std::shared_ptr<const NodeType> with_c_blocks(std::shared_ptr<const NodeType> type, const mg_node_type& c_type);

/// The wrapper of a C type that with_c_blocks put behind `type`, or nullptr when it put none.
const NodeType* c_type_behind_blocks(const NodeType& type);

}  // namespace mechgraph::detail
