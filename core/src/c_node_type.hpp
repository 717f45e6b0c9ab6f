#pragma once
// A node type of an SDK 1.x plugin (mg_node_type, sdk/include/mechgraph/c/node.h) behind the
// host's one node interface, NodeType: the evaluator, sweeps, the conformance kit and every writer
// use it like any other type. Its description is converted once (c_node_description.hpp); each
// evaluation passes the parameters and inputs as C views (no copies of arrays) and collects the
// outputs through the eval suite. Private to libmechgraph.
#include <mechgraph/c/host.h>
#include <mechgraph/c/node.h>
#include <mechgraph/node.hpp>

#include <memory>
#include <string>

namespace mechgraph::detail {

/// The eval suite v1 the host gives C plugins (mechgraph.eval/1).
const mg_eval_suite_v1& c_eval_suite();

/// Wraps `type` (checked: PluginError naming `where` and the field on a malformed description).
std::shared_ptr<const NodeType> make_c_node_type(const mg_node_type& type, const std::string& where);

}  // namespace mechgraph::detail
