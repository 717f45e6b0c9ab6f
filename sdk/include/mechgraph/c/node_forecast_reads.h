/* mechgraph SDK 1.3: which parameters a node type's work forecast reads, an optional interface of
 * the node type that the host asks for through mg_node_type::query (node.h) by name and version,
 * beside mechgraph.node.forecast/1 (node_forecast.h), whose forecast it describes.
 *
 * A sweep checks its budget case by case before anything runs: it asks each node's forecast once
 * per case. A type that answers this interface says that its forecast reads the listed parameters
 * and the input sizes, and never looks at any other parameter; the host then asks once (per worker
 * thread) for all the cases of a sweep that vary none of the listed parameters and give the same
 * input sizes. The host reads the table once, when it loads the type, and only from a type that
 * answers mechgraph.node.forecast/1. The C++ layer answers it for a NodeType that also implements
 * mechgraph::ForecastReads (node.hpp).
 *
 * The contract (the conformance kit checks it: each parameter not listed, changed, must leave the
 * forecast as it was):
 *  - every parameter the forecast reads is listed; one listed that it does not read costs only
 *    speed (the forecast is asked per case when a sweep varies it);
 *  - the table is static: the same answer for the type as long as the process lives.
 *
 * A type that does not answer (query NULL or answering NULL: every 1.0 to 1.2 plugin), or answers
 * with an index out of range, has its forecast asked case by case, as before.
 */
#ifndef MECHGRAPH_C_NODE_FORECAST_READS_H
#define MECHGRAPH_C_NODE_FORECAST_READS_H

#include <mechgraph/c/base.h>
#include <mechgraph/c/node.h>

MG_EXTERN_C_BEGIN

#define MG_NODE_FORECAST_READS "mechgraph.node.forecast_reads" /* version 1 */

/* Frozen with mechgraph.node.forecast_reads version 1. */
typedef struct mg_node_forecast_reads_v1 {
  uint32_t struct_size;
  const uint32_t* params; /* indices into desc->params: the parameters the forecast reads */
  size_t param_count;
} mg_node_forecast_reads_v1;

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_NODE_FORECAST_READS_H */
