/* mechgraph SDK 1.1: a node type's own work forecast, an optional interface of the node type that
 * the host asks for through mg_node_type::query (node.h) by name and version. A type that does not
 * answer it (query NULL, or query returning NULL: every 1.0 plugin) is counted by the conventions
 * of docs/writing-plugins.md ("Counts of work"): parameters named *points, *samples, *bins,
 * revolutions, list lengths. The host asks before anything runs, to refuse a scene beyond the
 * user's budget (--max-work, --max-memory) naming the node and the parameter behind it; the C++
 * layer answers it with NodeType::forecast.
 */
#ifndef MECHGRAPH_C_NODE_FORECAST_H
#define MECHGRAPH_C_NODE_FORECAST_H

#include <mechgraph/c/base.h>
#include <mechgraph/c/node.h>

MG_EXTERN_C_BEGIN

#define MG_NODE_FORECAST "mechgraph.node.forecast" /* version 1 */

/* What one evaluation will cost. Frozen with mechgraph.node.forecast version 1. */
typedef struct mg_work_forecast {
  double items;       /* work items of one evaluation (one is about a cam law at one angle, 0.1-1 us) */
  double memory;      /* bytes held at the peak of one evaluation, outputs included */
  double output_size; /* how large its output is for the nodes downstream: a law's smooth pieces, a
                         curve's points; 1 for a small value */
} mg_work_forecast;

typedef struct mg_node_forecast_v1 {
  uint32_t struct_size;
  /* The cost of one evaluation with `params` (desc->param_count entries as evaluate receives them:
     SI, ranges checked, defaults filled) on inputs of `input_sizes` (desc->input_count entries: the
     largest output_size of the nodes connected to each input, 1 when they say nothing, 0 for an
     input with nothing connected). Fills *out and writes to `driver` the parameter that makes it
     this large ("points = 300000"; may stay empty), and returns MG_OK; MG_ERR_UNSUPPORTED lets the
     host count by the conventions. Cheap (no evaluation; at most a look at a file's size),
     re-entrant; a negative or NaN figure is taken as no bound at all (the budget refuses it). */
  mg_status (*forecast)(const mg_node_type* self, const mg_param_value* params, const double* input_sizes,
                        mg_work_forecast* out, mg_text_sink driver);
} mg_node_forecast_v1;

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_NODE_FORECAST_H */
