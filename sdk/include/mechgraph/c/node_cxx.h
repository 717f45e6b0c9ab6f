/* mechgraph SDK 1.5: the C++ node type behind a node type, an optional interface of the node type
 * (node.h) that the host asks for through mg_node_type::query by name and version.
 *
 * A node type made by the C++ layer (MECHGRAPH_PLUGIN_1) is a C++ mechgraph::NodeType behind the C
 * description and evaluate function of node.h. Through C, every evaluation lays the parameters and
 * inputs out as C views, and the plugin's side copies them into its own sets, evaluates, and hands
 * each output back through the eval suite. When the host's C++ layer is binary-identical to the
 * plugin's, that is waste: both agree on every class layout, vtable and standard-library type a
 * NodeType touches, so the host may call the C++ type itself, as it calls a type of its own.
 *
 * `abi_key` is the key of mechgraph.object.cxx/1 (object_cxx.h): the SDK version, a digest of the
 * SDK's headers, the compiler and its major version, the standard library and its ABI switches
 * (mechgraph/detail/cxx_abi_key.hpp). A host uses `shared_type` only when the key equals its own
 * byte for byte; any other host (another compiler, another SDK release, a host that checks the C
 * boundary on purpose) ignores this interface and keeps to the C description and evaluate
 * function, which stay complete. The pointer it gives means nothing in C.
 *
 * A type whose ports carry a plugin's private interface is still read through C: the host names
 * such an interface after its plugin, which only the C description does.
 */
#ifndef MECHGRAPH_C_NODE_CXX_H
#define MECHGRAPH_C_NODE_CXX_H

#include <mechgraph/c/base.h>
#include <mechgraph/c/node.h>

MG_EXTERN_C_BEGIN

#define MG_NODE_CXX "mechgraph.node.cxx" /* version 1, optional */

/* Frozen with mechgraph.node.cxx version 1. */
typedef struct mg_node_cxx_v1 {
  uint32_t struct_size;
  const char* abi_key; /* NUL-terminated, static */
  /* The type's std::shared_ptr<const mechgraph::NodeType>, valid while the plugin is loaded; the
     host copies it (a reference of its own). */
  const void* (*shared_type)(const mg_node_type* self);
} mg_node_cxx_v1;

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_NODE_CXX_H */
