/* mechgraph SDK 1.4: the C++ object behind a domain object, an optional interface of the object
 * (object.h) that its consumer asks for through mg_object_vtbl::query by name and version.
 *
 * A domain object made by the C++ layer is a C++ object (the classes of mechgraph/domain) behind a C
 * vtable. A consumer that sees it only through C pays a call through the table for every query
 * (a search over a cam law asks for hundreds of points) and a view object per case. When the
 * consumer's C++ layer is binary-identical to the producer's, it may use the C++ object itself:
 * both then agree on every class layout, vtable and standard-library type it would touch.
 *
 * `abi_key` says what the producer's C++ layer is: the SDK version, a digest of the SDK's headers,
 * the compiler and its major version, the standard library and its ABI switches
 * (mechgraph/detail/cxx_abi_key.hpp). A consumer uses the two functions only when the key equals
 * its own byte for byte; any other consumer (another compiler, another SDK, a plugin written in C)
 * ignores this interface and keeps to the object's C tables, which stay complete. The pointers it
 * gives mean nothing in C. The same rule as pybind11's internals id, which lets extension modules
 * share C++ types only under one compiler, standard library and ABI.
 *
 * Only objects of the SDK's own interfaces answer it (cam_law, valve_motion, follower, joint_play,
 * fit, spring_model, spring): a plugin's private interface has no C++ class in the SDK, so its
 * layout is no part of the key.
 */
#ifndef MECHGRAPH_C_OBJECT_CXX_H
#define MECHGRAPH_C_OBJECT_CXX_H

#include <mechgraph/c/object.h>
#include <mechgraph/c/node_block.h>

MG_EXTERN_C_BEGIN

#define MG_OBJECT_CXX "mechgraph.object.cxx" /* version 1, optional */

/* Frozen with mechgraph.object.cxx version 1. */
typedef struct mg_object_cxx_v1 {
  uint32_t struct_size;
  const char* abi_key; /* NUL-terminated, static */
  /* The object's std::shared_ptr<const mechgraph::DomainObject>, valid while the object lives; the
     consumer copies it (a reference of its own). */
  const void* (*shared_object)(const mg_object* self);
  /* The std::shared_ptr<const mechgraph::DomainBlock> that `block` (node_block.h) was exported
     from, when the library that answers made it; NULL for another library's block. Valid while the
     block lives; the consumer copies it. */
  const void* (*shared_block)(const mg_object_block* block);
} mg_object_cxx_v1;

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_OBJECT_CXX_H */
