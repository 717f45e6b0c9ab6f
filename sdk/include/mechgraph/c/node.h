/* mechgraph SDK 1.x: node types (docs/design/sdk-1.0.md, section 1.4).
 *
 * A node type describes itself (mg_node_desc: parameters, ports, effects, work counters, output
 * dependencies, angle frames, notes) and evaluates: a pure, re-entrant function of its parameters
 * and inputs that may run on many threads at once. It reports through the eval suite (host.h):
 * outputs by index, errors through fail() with MG_ERR_NODE, work counters, notes; it polls
 * cancelled() in long loops. It never returns NaN or Inf: the host checks.
 *
 * Required prefixes. A host reads a description's fields up to these whatever the writer's
 * struct_size, and refuses a shorter struct; every field after them may be absent in a writer's
 * struct (an older 1.x) and then counts as its default (NULL, 0; MG_NO_FRAME for a frame). A
 * zeroed field means its default everywhere:
 *   mg_node_type  up to evaluate          mg_node_desc    up to output_count
 *   mg_param_decl up to field_count       mg_port_decl    up to flags
 *   mg_counter_decl up to name            mg_effect_decl  whole
 *   mg_plugin (plugin.h) up to node_types
 *   mg_angle_frame, mg_note_decl, mg_presentation, mg_channel_decl (present.h): whole, as in 1.0
 */
#ifndef MECHGRAPH_C_NODE_H
#define MECHGRAPH_C_NODE_H

#include <mechgraph/c/base.h>
#include <mechgraph/c/host.h>
#include <mechgraph/c/present.h>
#include <mechgraph/c/value.h>

MG_EXTERN_C_BEGIN

#define MG_PARAM_NUMBER 1
#define MG_PARAM_INTEGER 2
#define MG_PARAM_CHOICE 3
#define MG_PARAM_TEXT 4
#define MG_PARAM_NUMBER_LIST 5
#define MG_PARAM_RECORD_LIST 6

#define MG_PF_REQUIRED 0x01u      /* a scene must give it (unless it has a default) */
#define MG_PF_KNOB 0x02u          /* an accuracy knob: `mechgraph bench` varies it */
#define MG_PF_PATH 0x04u          /* text naming a file, resolved against the scene's folder */
#define MG_PF_HAS_DEFAULT 0x08u
#define MG_PF_HAS_EXAMPLE 0x10u
#define MG_PF_MIN_EXCLUSIVE 0x20u
#define MG_PF_MAX_EXCLUSIVE 0x40u

struct mg_record;

/* A parameter's value: in declarations (default, example) and as evaluate receives it, in SI.
   Frozen. */
typedef struct mg_param_value {
  int32_t kind;    /* MG_PARAM_* */
  int32_t present; /* 0: an optional parameter without default, absent */
  double number;   /* number, integer */
  mg_str text;     /* choice, text */
  const double* numbers; /* number_list */
  size_t number_count;
  const struct mg_record* records; /* record_list */
  size_t record_count;
} mg_param_value;

/* One record of a record list: its fields in declared order. Frozen. */
typedef struct mg_record {
  const mg_param_value* fields;
  size_t field_count;
} mg_record;

typedef struct mg_param_decl {
  uint32_t struct_size;
  const char* name;
  int32_t kind; /* MG_PARAM_* */
  mg_dim dim;
  const char* doc;
  uint32_t flags;           /* MG_PF_* */
  double min, max;          /* SI; -inf/+inf when open */
  const char* range_reason; /* why the range; NULL: none said */
  mg_param_value default_value; /* MG_PF_HAS_DEFAULT */
  mg_param_value example_value; /* MG_PF_HAS_EXAMPLE */
  const char* const* choices;   /* MG_PARAM_CHOICE; a knob lists the most accurate first */
  size_t choice_count;
  const struct mg_param_decl* fields; /* MG_PARAM_RECORD_LIST (strided, MG_ELEMENT) */
  size_t field_count;
  const char* display_unit; /* "mm"; NULL: SI */
  const char* label;        /* NULL: the name with '_' as ' ' */
  int32_t angle_frame;      /* MG_FRAME(i) of mg_node_desc::frames, MG_NO_FRAME (0) none */
} mg_param_decl;

#define MG_PORT_MULTIPLE 0x1u /* an input that takes a list of connections */
#define MG_PORT_OPTIONAL 0x2u /* an input that may stay unconnected */

typedef struct mg_port_decl {
  uint32_t struct_size;
  const char* name;
  int32_t kind; /* MG_VALUE_* */
  mg_dim dim;   /* scalars and series; tables carry it per channel */
  const char* doc;
  const char* interface;      /* objects: "mechgraph.cam_law" */
  uint32_t interface_version; /* objects: 1 */
  uint32_t flags;             /* MG_PORT_* */
  const char* display_unit;
  const char* label;
  int32_t angle_frame;                          /* MG_FRAME(i), MG_NO_FRAME (0) none */
  const struct mg_presentation* presentation;   /* tables and series; NULL: plain */
} mg_port_decl;

typedef struct mg_effect_decl {
  uint32_t struct_size;
  const char* name;
  const char* doc;
  const char* const* outputs; /* outputs that exist only while it is on */
  size_t output_count;
  const char* const* params; /* parameters read only while it is on */
  size_t param_count;
} mg_effect_decl;

typedef struct mg_counter_decl {
  uint32_t struct_size;
  const char* name; /* "samples", "evaluations" */
  const char* doc;
} mg_counter_decl;

/* Which inputs an output depends on; an output not listed depends on all inputs. Frozen. */
typedef struct mg_output_deps {
  const char* output;
  const char* const* inputs;
  size_t input_count;
} mg_output_deps;

typedef struct mg_node_desc {
  uint32_t struct_size;
  const char* type; /* "plugin.kind" */
  int32_t version;  /* bump when results change: part of the memo key */
  const char* summary;
  const mg_param_decl* params; /* every array of growable structs is strided (MG_ELEMENT) */
  size_t param_count;
  const mg_port_decl* inputs;
  size_t input_count;
  const mg_port_decl* outputs;
  size_t output_count;
  const mg_effect_decl* effects;
  size_t effect_count;
  const mg_counter_decl* counters;
  size_t counter_count;
  const mg_output_deps* deps;
  size_t dep_count;
  const mg_angle_frame* frames;
  size_t frame_count;
  const mg_note_decl* notes;
  size_t note_count;
} mg_node_desc;

typedef struct mg_eval_args {
  uint32_t struct_size;
  const mg_param_value* params; /* desc->param_count entries, declaration order, SI, checked */
  const mg_input* inputs;       /* desc->input_count entries, declaration order */
  /* SDK 1.4 (read it when MG_HAS_FIELD says so): desc->output_count entries, 1 for an output read
     downstream, else 0, what mg_eval_suite_v1::wanted answers for each; NULL: ask the suite. */
  const int32_t* wanted;
} mg_eval_args;

typedef struct mg_node_type {
  uint32_t struct_size;
  const mg_node_desc* desc;
  void* impl; /* the plugin's own */
  /* Pure and re-entrant; may run on many threads at once. Borrowed: args and everything they reach,
     for the call only. Returns MG_OK or a status (after fail() for MG_ERR_NODE). Must not throw. */
  mg_status (*evaluate)(const struct mg_node_type* self, const mg_eval_args* args, mg_eval_ctx* ctx);
  /* Optional (NULL: none). The node type's table of interface `name` at `version`, or NULL: how a
     node type offers a capability that came after 1.0 (several cases in one call, its own work
     forecast ...) without changing this struct, as mg_object_vtbl::query does for objects. The
     same pointer for the same question; tables live until the process ends. SDK 1.0 defines no
     node type interface, so a 1.0 host never calls it; SDK 1.1 defines mechgraph.node.forecast
     (node_forecast.h), which a 1.1 host asks for once per type. */
  const void* (*query)(const struct mg_node_type* self, const char* name, uint32_t version);
} mg_node_type;

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_NODE_H */
