/* mechgraph SDK 1.x: what the host gives a plugin (docs/design/sdk-1.0.md, section 1.3).
 *
 * The host passes an mg_host to the plugin's entry. Everything else the host offers is a suite: a
 * C function table fetched by name and version (OpenFX's fetchSuite). A suite never changes once
 * shipped; a new capability is a new suite or a new version of one, and a plugin asks for the
 * newest it knows first and falls back. fetch returns NULL for a suite the host does not have.
 */
#ifndef MECHGRAPH_C_HOST_H
#define MECHGRAPH_C_HOST_H

#include <mechgraph/c/base.h>

MG_EXTERN_C_BEGIN

struct mg_series;
struct mg_table;
struct mg_object;

typedef struct mg_host {
  uint32_t struct_size;
  uint16_t sdk_major, sdk_minor; /* the host's SDK */
  const char* host_name;         /* "mechgraph 0.2.0" */
  void* host_data;               /* opaque; the first argument of fetch */
  /* A suite by name and version, or NULL. The same pointer on every call, valid until the process
     ends (plugins are never unloaded). */
  const void* (*fetch)(void* host_data, const char* suite, uint32_t version);
} mg_host;

#define MG_SUITE_LOG "mechgraph.log"       /* v1: plugin-level messages outside an evaluation */
#define MG_SUITE_EVAL "mechgraph.eval"     /* v1: everything a node does while it evaluates    */
#define MG_SUITE_MEMORY "mechgraph.memory" /* v1: host-owned buffers for C plugins             */

/* One evaluation call; opaque, valid during the call only. */
typedef struct mg_eval_ctx mg_eval_ctx;

/* Log levels. A host shows a level above MG_LOG_WARN as MG_LOG_WARN, below MG_LOG_DEBUG as
   MG_LOG_DEBUG. */
#define MG_LOG_DEBUG 0
#define MG_LOG_INFO 1
#define MG_LOG_WARN 2

typedef struct mg_log_suite_v1 {
  uint32_t struct_size;
  void (*log)(int32_t level, const char* plugin_id, mg_str message);
} mg_log_suite_v1;

typedef struct mg_eval_suite_v1 {
  uint32_t struct_size;
  /* Queries. Indices are positions in the node type's own declaration (mg_node_desc). */
  int32_t (*effect)(mg_eval_ctx* ctx, uint32_t effect_index); /* switched on: 1, else 0       */
  int32_t (*wanted)(mg_eval_ctx* ctx, uint32_t output_index); /* read downstream: 1, else 0   */
  int32_t (*cancelled)(mg_eval_ctx* ctx);                     /* poll; 1: return MG_ERR_CANCELLED */
  /* Reporting. */
  void (*log)(mg_eval_ctx* ctx, int32_t level, mg_str message);
  void (*add_work)(mg_eval_ctx* ctx, uint32_t counter_index, double amount);
  void (*note)(mg_eval_ctx* ctx, mg_str text);
  /* The error sink: names the parameter or input at fault (may be empty) and the limit broken.
     The node then returns MG_ERR_NODE. */
  void (*fail)(mg_eval_ctx* ctx, mg_str parameter, mg_str message);
  /* Outputs. A scalar is copied. Arrays are adopted: the host calls their owner.release once,
     also when it refuses them (and when set_* returns an error). An object: its one reference is
     taken over. A second set of the same output replaces the first. */
  void (*set_scalar)(mg_eval_ctx* ctx, uint32_t output_index, double value);
  mg_status (*set_series)(mg_eval_ctx* ctx, uint32_t output_index, const struct mg_series* series);
  mg_status (*set_table)(mg_eval_ctx* ctx, uint32_t output_index, const struct mg_table* table);
  mg_status (*set_object)(mg_eval_ctx* ctx, uint32_t output_index, const struct mg_object* object);
  /* Scratch memory, freed after evaluate returns: no malloc on hot paths. NULL on failure. */
  void* (*scratch)(mg_eval_ctx* ctx, size_t bytes, size_t align);
} mg_eval_suite_v1;

typedef struct mg_memory_suite_v1 {
  uint32_t struct_size;
  void* (*alloc)(size_t bytes, size_t align); /* NULL on failure */
  void (*free)(void* p);                      /* only for alloc's pointers; NULL is ignored */
  mg_owner (*owner_of)(void* p);              /* an owner whose release frees p */
} mg_memory_suite_v1;

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_HOST_H */
