/* A plugin written in plain C that evaluates blocks of sweep cases (c/node_block.h,
   mechgraph.node.block/1, SDK 1.2): cblk.square, y = x^2 + offset, where offset is an optional
   scalar input (0 when unconnected). A case with x above 10 is refused: evaluate fails it with a
   message naming x, evaluate_block fails that case alone (its status) and the host redoes it.
   Built as:
     test_c_blocks          the contract kept
     test_c_blocks_broken   (C_BLOCKS_BROKEN) every block call reports work on an undeclared counter:
                            a broken contract, so the host drops each block and runs every case alone
   tests/core/c_block_test.cpp sweeps it both ways. */
#include <mechgraph/c/base.h>
#include <mechgraph/c/host.h>
#include <mechgraph/c/node.h>
#include <mechgraph/c/node_block.h>
#include <mechgraph/c/plugin.h>

#include <string.h>

static const mg_eval_suite_v1* eval;

static mg_str str(const char* s) {
  mg_str out;
  out.data = s;
  out.size = strlen(s);
  return out;
}

static const char refusal[] = "x above 10 is refused here";

static mg_status square(const mg_node_type* self, const mg_eval_args* args, mg_eval_ctx* ctx) {
  const double x = args->params[0].number;
  const double offset = args->inputs[0].count > 0 ? args->inputs[0].values[0].u.scalar : 0.0;
  (void)self;
  if (x > 10.0) {
    eval->fail(ctx, str("x"), str(refusal));
    return MG_ERR_NODE;
  }
  eval->add_work(ctx, 0, 1.0);
  eval->set_scalar(ctx, 0, x * x + offset);
  return MG_OK;
}

static mg_status square_supported(const mg_node_type* self, const mg_block_request* request) {
  (void)self;
  (void)request;
  return MG_OK;
}

/* The same formula as square(), case by case. */
static mg_status square_block(const mg_node_type* self, const mg_block_args* a) {
  const mg_block_column x = a->param_columns[0].values ? a->param_columns[0] : (mg_block_column){&a->params[0].number, 0};
  const mg_block_column offset = a->inputs[0].scalar;
  double* y = a->scalar_outputs[0];
  double work = 0.0;
  size_t i;
  (void)self;
  for (i = 0; i < a->size; ++i) {
    const double xi = x.values[i * x.stride];
    if (a->status[i] != MG_OK) continue;
    if (xi > 10.0) {
      a->status[i] = MG_ERR_NODE;
      continue;
    }
    if (y) y[i] = xi * xi + (offset.values ? offset.values[i * offset.stride] : 0.0);
    work += 1.0;
  }
#ifdef C_BLOCKS_BROKEN
  a->host->add_work(a->ctx, 7, work);
#else
  a->host->add_work(a->ctx, 0, work);
#endif
  return MG_OK;
}

static const mg_node_block_v1 block_table = {sizeof(mg_node_block_v1), square_supported, square_block};
static const void* square_query(const mg_node_type* self, const char* name, uint32_t version) {
  (void)self;
  return name && version == 1 && strcmp(name, MG_NODE_BLOCK) == 0 ? &block_table : NULL;
}

static mg_param_decl params[1];
static mg_port_decl inputs[1], outputs[1];
static const mg_counter_decl counters[1] = {{sizeof(mg_counter_decl), "squares", "squares made"}};
static mg_node_desc desc;
static mg_node_type square_type;
static const mg_node_type* types[1] = {&square_type};
static mg_plugin plugin;

const mg_plugin* mechgraph_plugin_entry_1(const mg_host* host, mg_text_sink why) {
  static const char no_eval[] = "this host has no mechgraph.eval suite version 1";
  eval = (const mg_eval_suite_v1*)host->fetch(host->host_data, MG_SUITE_EVAL, 1);
  if (!eval) {
    why.append(why.self, no_eval, sizeof no_eval - 1);
    return NULL;
  }
  memset(params, 0, sizeof params);
  params[0].struct_size = sizeof params[0];
  params[0].name = "x";
  params[0].kind = MG_PARAM_NUMBER;
  params[0].doc = "the number squared";
  params[0].flags = MG_PF_REQUIRED | MG_PF_HAS_DEFAULT;
  params[0].min = -1e6;
  params[0].max = 1e6;
  params[0].default_value.kind = MG_PARAM_NUMBER;
  params[0].default_value.present = 1;
  params[0].default_value.number = 2.0;
  params[0].angle_frame = MG_NO_FRAME;
  memset(inputs, 0, sizeof inputs);
  inputs[0].struct_size = sizeof inputs[0];
  inputs[0].name = "offset";
  inputs[0].kind = MG_VALUE_SCALAR;
  inputs[0].doc = "added to the square";
  inputs[0].flags = MG_PORT_OPTIONAL;
  inputs[0].angle_frame = MG_NO_FRAME;
  memset(outputs, 0, sizeof outputs);
  outputs[0].struct_size = sizeof outputs[0];
  outputs[0].name = "y";
  outputs[0].kind = MG_VALUE_SCALAR;
  outputs[0].doc = "x^2 + offset";
  outputs[0].angle_frame = MG_NO_FRAME;
  memset(&desc, 0, sizeof desc);
  desc.struct_size = sizeof desc;
  desc.type = "cblk.square";
  desc.version = 1;
  desc.summary = "a square, also in blocks of cases (a plugin written in C)";
  desc.params = params;
  desc.param_count = 1;
  desc.inputs = inputs;
  desc.input_count = 1;
  desc.outputs = outputs;
  desc.output_count = 1;
  desc.counters = counters;
  desc.counter_count = 1;
  memset(&square_type, 0, sizeof square_type);
  square_type.struct_size = sizeof square_type;
  square_type.desc = &desc;
  square_type.evaluate = square;
  square_type.query = square_query;
  memset(&plugin, 0, sizeof plugin);
  plugin.struct_size = sizeof plugin;
  plugin.sdk_major = MG_SDK_MAJOR;
  plugin.sdk_minor = MG_SDK_MINOR;
  plugin.plugin_id = "cblk";
  plugin.plugin_version = "1.0.0";
  plugin.sdk_version = "1.2.0";
  plugin.built_with = "C";
  plugin.node_type_count = 1;
  plugin.node_types = types;
  return &plugin;
}
