/* mechgraph SDK 1.2: blocks of cases, an optional interface of the node type that the host asks for
 * through mg_node_type::query (node.h) by name and version, as it asks for mechgraph.node.forecast.
 * A sweep's block is n cases of one graph that differ only in some number parameters; a node that
 * answers this interface evaluates all n at once (structure of arrays): varied parameters and
 * scalar inputs come as columns, scalar outputs go out as columns, domain objects travel as blocks
 * (an array of objects, one per case or one for every case, plus the columns of figures an
 * interface's block form names). The C++ layer answers it for a NodeType that also implements
 * mechgraph::BlockEvaluation (mechgraph/block.hpp), whose contract this is:
 *
 *  - every case a block does not fail gets the very numbers evaluate() gives it alone;
 *  - a case the node cannot do is failed in `status` (its own status, not MG_OK): the host redoes
 *    it alone through evaluate(), whose message names the fault exactly as a run would (the
 *    message is the single evaluation's, so the block carries none);
 *  - supported() says, before any case runs, whether this node (its fixed parameters, the outputs
 *    read of it, the parameters that vary) can go on the block path; the host uses blocks only when
 *    every node a sweep needs says yes;
 *  - evaluate_block() is pure and re-entrant like evaluate(), and may run on many threads at once.
 *
 * A type that does not answer (query NULL or answering NULL: every 1.0 and 1.1 plugin) has every
 * case of a sweep evaluated alone, as before.
 */
#ifndef MECHGRAPH_C_NODE_BLOCK_H
#define MECHGRAPH_C_NODE_BLOCK_H

#include <mechgraph/c/base.h>
#include <mechgraph/c/node.h>
#include <mechgraph/c/object.h>

MG_EXTERN_C_BEGIN

#define MG_NODE_BLOCK "mechgraph.node.block" /* version 1 */

/* One number per case: case i's is values[i * stride]. stride 1: one per case; stride 0: one for
   every case. Frozen with mechgraph.node.block version 1. */
typedef struct mg_block_column {
  const double* values;
  size_t stride;
} mg_block_column;

/* A block of domain objects of one interface (the port's). `object_count` is the block's size or 1
   (one object for every case); objects[i] is case i's (objects[0] for every case when 1), NULL
   for a failed case. An interface's block form may name columns of figures beside the objects
   (c/domain/valve_motion_block.h: a valve motion block is its cases' cam laws and five figures);
   `figures` holds figure_count of them, each over the block's cases (stride 0 or 1). Without a
   block form the objects are the interface's own and there are no figures.
   As an output: handed over to the host with one reference to each non-NULL object, which
   owner.release (called exactly once, by the host) gives back with the arrays; owner.release NULL
   only for static storage that holds no references. As an input: borrowed for the call; the host
   may pass a producer's block on as it came, so the consumer never calls its owner. `origin`
   identifies the producing library's SDK layer (as mg_object_vtbl::origin): a library that finds
   its own origin on an input may take owner.ctx for its own block (no copy). Frozen with
   mechgraph.node.block version 1. */
typedef struct mg_object_block {
  uint32_t struct_size;
  size_t object_count;
  const mg_object* const* objects;
  const mg_block_column* figures;
  size_t figure_count;
  mg_owner owner;
  const void* origin;
} mg_object_block;

/* What the host gives for each declared input: a scalar port's column, or an object port's block
   (NULL for a scalar port). An unconnected input: {NULL, 0} and NULL. */
typedef struct mg_block_input {
  mg_block_column scalar;
  const mg_object_block* objects;
} mg_block_input;

/* The node's view of the host during one block call (what mechgraph.eval gives evaluate, less
   the outputs): queries and reports by index in the node's own declaration. Work counters are
   summed over the block. */
typedef struct mg_block_ctx mg_block_ctx; /* opaque, one per block call */
typedef struct mg_block_host_v1 {
  uint32_t struct_size;
  int32_t (*effect)(mg_block_ctx*, uint32_t effect_index);
  int32_t (*wanted)(mg_block_ctx*, uint32_t output_index);
  int32_t (*cancelled)(mg_block_ctx*);
  void (*log)(mg_block_ctx*, int32_t level, mg_str message);
  void (*add_work)(mg_block_ctx*, uint32_t counter_index, double amount);
} mg_block_host_v1;

/* What the host asks before it plans blocks. */
typedef struct mg_block_request {
  uint32_t struct_size;
  const mg_param_value* params; /* desc->param_count entries, as evaluate receives them */
  const int32_t* wanted;        /* desc->output_count entries: 1 when read downstream */
  const int32_t* varied;        /* desc->param_count entries: 1 when it varies from case to case */
} mg_block_request;

typedef struct mg_block_args {
  uint32_t struct_size;
  size_t size;                          /* the cases of the block */
  const mg_param_value* params;         /* desc->param_count entries, as evaluate receives them; a
                                           varied one holds some case's value: read its column */
  const mg_block_column* param_columns; /* desc->param_count entries: a varied number's column,
                                           {NULL, 0} for a parameter that does not vary */
  const mg_block_input* inputs;         /* desc->input_count entries */
  double* const* scalar_outputs;        /* desc->output_count entries: `size` numbers to fill for a
                                           scalar output read downstream, NULL for the others */
  mg_object_block* object_outputs;      /* desc->output_count entries, zeroed by the host: the node
                                           fills the one of each object output read downstream */
  int32_t* status;                      /* `size` entries: MG_OK for a live case, which the node
                                           sets to another status to fail it; a case that comes in
                                           failed is skipped */
  const mg_block_host_v1* host;
  mg_block_ctx* ctx;
} mg_block_args;

typedef struct mg_node_block_v1 {
  uint32_t struct_size;
  /* MG_OK when evaluate_block can make every wanted output for these parameters, with these
     parameters varied; MG_ERR_UNSUPPORTED when not. Cheap, re-entrant. Any other status counts
     as "not". */
  mg_status (*supported)(const mg_node_type* self, const mg_block_request* request);
  /* Evaluates the live cases of the block (borrowed: args and everything they reach, for the call
     only, but the object outputs handed over). MG_OK: `status` says which cases failed. Anything
     else: the host drops the block's outputs (releasing what was handed over) and evaluates every
     case alone, which gives each its message. */
  mg_status (*evaluate_block)(const mg_node_type* self, const mg_block_args* args);
} mg_node_block_v1;

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_NODE_BLOCK_H */
