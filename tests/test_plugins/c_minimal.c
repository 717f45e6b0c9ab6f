/* A plugin written in C against the SDK 1.x boundary alone (sdk/include/mechgraph/c): no C++, no
   link to any mechgraph library. One node type, cmin.parabola: a table y = height * x^2 over
   x in [0, 1] and its peak, refusing a height above `limit` through the eval suite's error sink.
   It offers its own work forecast (mechgraph.node.forecast/1, SDK 1.1) through mg_node_type::query:
   1000 items a point, driven by "points", and says that the forecast reads "points" only
   (mechgraph.node.forecast_reads/1, SDK 1.3).
   Built as it is and, with C_MINIMAL_VARIANT, as the loader tests' variants:
     C_MINIMAL_OLDER      structs as an older 1.x wrote them (shorter struct_size; strided arrays),
                          a 1.0 plugin: no query, so the host counts its work by the conventions
     C_MINIMAL_NEWER      built against SDK 1.(host minor + 1): refused, naming both versions
     C_MINIMAL_REFUSES    the entry returns NULL with a reason
     C_MINIMAL_BAD_FRAME  a port names an angle frame the type does not declare: refused
     C_MINIMAL_POLLS      a second node type that works until the host cancels */
#include <mechgraph/c/plugin.h>
#include <mechgraph/c/node.h>
#include <mechgraph/c/node_forecast.h>
#include <mechgraph/c/node_forecast_reads.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const mg_eval_suite_v1* eval;

static mg_str str(const char* s) {
  mg_str out;
  out.data = s;
  out.size = strlen(s);
  return out;
}

static const mg_dim none = {0, 0, 0, 0, 0, 0, 0, 0};
static const mg_dim length = {1, 0, 0, 0, 0, 0, 0, 0};

enum { P_POINTS, P_HEIGHT, P_LIMIT, PARAM_COUNT };
enum { O_CURVE, O_PEAK, OUTPUT_COUNT };

/* The table's arrays in one block, freed by the host through the owner when it is done. */
typedef struct curve_block {
  mg_column channel;
  double values[]; /* x (rows), then y (rows) */
} curve_block;

static void release_block(void* ctx) { free(ctx); }

static mg_status parabola(const mg_node_type* self, const mg_eval_args* args, mg_eval_ctx* ctx) {
  const double height = args->params[P_HEIGHT].number;
  const double limit = args->params[P_LIMIT].number;
  const size_t rows = (size_t)args->params[P_POINTS].number;
  curve_block* block;
  mg_table table;
  size_t i;
  (void)self;
  if (height > limit) {
    eval->fail(ctx, str("height"), str("a height above the limit would not fit (height > limit)"));
    return MG_ERR_NODE;
  }
#ifndef C_MINIMAL_OLDER
  eval->add_work(ctx, 0, (double)rows); /* the older variant declares no counters */
#endif
  eval->set_scalar(ctx, O_PEAK, height);
  if (!eval->wanted(ctx, O_CURVE)) return MG_OK;
  block = (curve_block*)malloc(sizeof(curve_block) + 2 * rows * sizeof(double));
  if (!block) return MG_ERR_NO_MEMORY;
  for (i = 0; i < rows; ++i) {
    const double x = (double)i / (double)(rows - 1);
    block->values[i] = x;
    block->values[rows + i] = height * x * x;
  }
  block->channel.name = "y";
  block->channel.dim = length;
  block->channel.display_unit = "mm";
  block->channel.values = block->values + rows;
  memset(&table, 0, sizeof table);
  table.struct_size = sizeof table;
  table.rows = rows;
  table.axis.name = "x";
  table.axis.dim = none;
  table.axis.display_unit = NULL;
  table.axis.values = block->values;
  table.channels = &block->channel;
  table.channel_count = 1;
  table.owner.ctx = block;
  table.owner.release = release_block;
  eval->note(ctx, str("cmin: a parabola in C"));
  return eval->set_table(ctx, O_CURVE, &table);
}

#ifdef C_MINIMAL_OLDER
/* The port declaration as a hypothetical older 1.x had it: it ended at `flags`. */
typedef struct older_port_decl {
  uint32_t struct_size;
  const char* name;
  int32_t kind;
  mg_dim dim;
  const char* doc;
  const char* interface;
  uint32_t interface_version;
  uint32_t flags;
} older_port_decl;
static const older_port_decl outputs[OUTPUT_COUNT] = {
    {sizeof(older_port_decl), "curve", MG_VALUE_TABLE, {0, 0, 0, 0, 0, 0, 0, 0}, "y = height x^2 over x", NULL, 0, 0},
    {sizeof(older_port_decl), "peak", MG_VALUE_SCALAR, {1, 0, 0, 0, 0, 0, 0, 0}, "y at x = 1", NULL, 0, 0}};
#else
#ifdef C_MINIMAL_BAD_FRAME
#define PEAK_FRAME MG_FRAME(0) /* the type declares no frame */
#else
#define PEAK_FRAME MG_NO_FRAME
#endif
static const mg_port_decl outputs[OUTPUT_COUNT] = {
    {sizeof(mg_port_decl), "curve", MG_VALUE_TABLE, {0, 0, 0, 0, 0, 0, 0, 0}, "y = height x^2 over x", NULL, 0, 0, NULL,
     "parabola", MG_NO_FRAME, NULL},
    {sizeof(mg_port_decl), "peak", MG_VALUE_SCALAR, {1, 0, 0, 0, 0, 0, 0, 0}, "y at x = 1", NULL, 0, 0, "mm", "peak", PEAK_FRAME,
     NULL}};
#endif

#ifndef C_MINIMAL_OLDER
/* How many forecasts the host asked for, read by the host's tests (dlsym): a sweep that varies
   only `height` asks once per worker, one that varies `points` once per case. */
static _Atomic long forecasts_asked;
__attribute__((visibility("default"))) long cmin_forecasts_asked(void) { return forecasts_asked; }

static mg_status parabola_forecast(const mg_node_type* self, const mg_param_value* args, const double* input_sizes,
                                   mg_work_forecast* out, mg_text_sink driver) {
  static const char said[] = "points (1000 items a point)";
  ++forecasts_asked;
  (void)self;
  (void)input_sizes;
  out->items = 1000.0 * args[P_POINTS].number;
  out->memory = 16.0 * args[P_POINTS].number;
  out->output_size = args[P_POINTS].number;
  driver.append(driver.self, said, sizeof said - 1);
  return MG_OK;
}
static const mg_node_forecast_v1 forecast_table = {sizeof(mg_node_forecast_v1), parabola_forecast};
static const uint32_t forecast_params[] = {P_POINTS};
static const mg_node_forecast_reads_v1 forecast_reads_table = {sizeof(mg_node_forecast_reads_v1), forecast_params, 1};
static const void* parabola_query(const mg_node_type* self, const char* name, uint32_t version) {
  (void)self;
  if (version != 1) return NULL;
  if (strcmp(name, MG_NODE_FORECAST) == 0) return &forecast_table;
  return strcmp(name, MG_NODE_FORECAST_READS) == 0 ? &forecast_reads_table : NULL;
}
#endif

static mg_param_decl params[PARAM_COUNT];
#ifndef C_MINIMAL_OLDER
static const mg_counter_decl counters[1] = {{sizeof(mg_counter_decl), "points", "rows computed"}};
#endif
static mg_node_desc desc;
static mg_node_type parabola_type;

static void declare_number(mg_param_decl* p, const char* name, mg_dim dim, const char* doc, double fallback,
                           const char* unit) {
  memset(p, 0, sizeof *p);
  p->struct_size = sizeof *p;
  p->name = name;
  p->kind = MG_PARAM_NUMBER;
  p->dim = dim;
  p->doc = doc;
  p->flags = MG_PF_REQUIRED | MG_PF_HAS_DEFAULT | MG_PF_MIN_EXCLUSIVE;
  p->min = 0.0;
  p->max = INFINITY;
  p->default_value.kind = MG_PARAM_NUMBER;
  p->default_value.present = 1;
  p->default_value.number = fallback;
  p->display_unit = unit;
  p->angle_frame = MG_NO_FRAME;
}

static void declare(void) {
  declare_number(&params[P_POINTS], "points", none, "rows of the table", 5.0, NULL);
  params[P_POINTS].kind = MG_PARAM_INTEGER;
  params[P_POINTS].default_value.kind = MG_PARAM_INTEGER;
  params[P_POINTS].flags = MG_PF_REQUIRED | MG_PF_HAS_DEFAULT | MG_PF_KNOB;
  params[P_POINTS].min = 2.0;
  params[P_POINTS].max = 100000.0;
  params[P_POINTS].range_reason = "a table a person reads";
  declare_number(&params[P_HEIGHT], "height", length, "y at x = 1", 0.01, "mm");
  declare_number(&params[P_LIMIT], "limit", length, "the largest height accepted", 1.0, "mm");
  memset(&desc, 0, sizeof desc);
#ifdef C_MINIMAL_OLDER
  desc.struct_size = (uint32_t)offsetof(mg_node_desc, effects); /* no effects, counters, frames ... */
#else
  desc.struct_size = sizeof desc;
  desc.counters = counters;
  desc.counter_count = 1;
#endif
  desc.type = "cmin.parabola";
  desc.version = 1;
  desc.summary = "a parabola as a table (a plugin written in C)";
  desc.params = params;
  desc.param_count = PARAM_COUNT;
  desc.outputs = (const mg_port_decl*)(const void*)outputs;
  desc.output_count = OUTPUT_COUNT;
  memset(&parabola_type, 0, sizeof parabola_type);
  parabola_type.struct_size = sizeof parabola_type;
  parabola_type.desc = &desc;
  parabola_type.evaluate = parabola;
#ifndef C_MINIMAL_OLDER
  parabola_type.query = parabola_query;
#endif
}

#ifdef C_MINIMAL_POLLS
/* cmin.wait: counts up to `steps`, polling cancelled() at each; MG_ERR_CANCELLED when asked. */
static mg_status wait_node(const mg_node_type* self, const mg_eval_args* args, mg_eval_ctx* ctx) {
  const double steps = args->params[0].number;
  double done = 0.0;
  (void)self;
  while (done < steps) {
    if (eval->cancelled(ctx)) return MG_ERR_CANCELLED;
    done += 1.0;
  }
  eval->set_scalar(ctx, 0, done);
  return MG_OK;
}
static mg_param_decl wait_params[1];
static const mg_port_decl wait_outputs[1] = {
    {sizeof(mg_port_decl), "done", MG_VALUE_SCALAR, {0, 0, 0, 0, 0, 0, 0, 0}, "steps done", NULL, 0, 0, NULL, NULL, MG_NO_FRAME, NULL}};
static mg_node_desc wait_desc;
static mg_node_type wait_type;
static void declare_wait(void) {
  declare_number(&wait_params[0], "steps", none, "steps to count", 1000.0, NULL);
  memset(&wait_desc, 0, sizeof wait_desc);
  wait_desc.struct_size = sizeof wait_desc;
  wait_desc.type = "cmin.wait";
  wait_desc.version = 1;
  wait_desc.summary = "counts, polling the host's cancellation";
  wait_desc.params = wait_params;
  wait_desc.param_count = 1;
  wait_desc.outputs = wait_outputs;
  wait_desc.output_count = 1;
  memset(&wait_type, 0, sizeof wait_type);
  wait_type.struct_size = sizeof wait_type;
  wait_type.desc = &wait_desc;
  wait_type.evaluate = wait_node;
}
static const mg_node_type* types[2] = {&parabola_type, &wait_type};
#define TYPE_COUNT 2
#else
static const mg_node_type* types[1] = {&parabola_type};
#define TYPE_COUNT 1
#endif

static mg_plugin plugin;

const mg_plugin* mechgraph_plugin_entry_1(const mg_host* host, mg_text_sink why) {
  static const char no_eval[] = "this host has no mechgraph.eval suite version 1";
  eval = (const mg_eval_suite_v1*)host->fetch(host->host_data, MG_SUITE_EVAL, 1);
  if (!eval) {
    why.append(why.self, no_eval, sizeof no_eval - 1);
    return NULL;
  }
#ifdef C_MINIMAL_REFUSES
  {
    static const char reason[] = "no licence for this machine (cmin refuses to load)";
    why.append(why.self, reason, sizeof reason - 1);
    return NULL;
  }
#endif
  declare();
#ifdef C_MINIMAL_POLLS
  declare_wait();
#endif
  memset(&plugin, 0, sizeof plugin);
  plugin.struct_size = sizeof plugin;
  plugin.sdk_major = MG_SDK_MAJOR;
  plugin.sdk_minor = MG_SDK_MINOR;
#ifdef C_MINIMAL_OLDER
  plugin.struct_size = (uint32_t)offsetof(mg_plugin, interface_count);
  plugin.sdk_minor = 0;
#endif
#ifdef C_MINIMAL_NEWER
  plugin.sdk_minor = MG_SDK_MINOR + 1;
#endif
  plugin.plugin_id = "cmin";
  plugin.plugin_version = "1.0.0";
  plugin.sdk_version = "1.0.0";
  plugin.built_with = "C";
  plugin.node_type_count = TYPE_COUNT;
  plugin.node_types = types;
  return &plugin;
}
