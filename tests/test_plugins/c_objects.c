/* A plugin written in C whose nodes pass a domain object between them through the SDK 1.x
   boundary (sdk/include/mechgraph/c/object.h, domain/cam_law.h):
     cobj.law   outputs a cam law (mechgraph.cam_law/1): h = lift cos^2(pi phi / (2 w)) on (-w, w);
                with `wide: 1` its event reaches beyond +-180 deg, which the host must refuse
     cobj.peak  takes a cam law and outputs its lift at the nose, through the law's C table
     cobj.live  outputs how many of this plugin's objects are alive (releases are counted)
     cobj.gauge outputs an object of this plugin's private interface "cobj.gauge" at version 2 (its
                table answers versions 1 and 2)
     cobj.read_gauge takes a "cobj.gauge" of version 2 or later and outputs its reading
     cobj.fit   outputs a fit (mechgraph.fit/1, SDK 1.1, plain data): 20 mm, hole +21/0 um uniform,
                shaft -7/-20 um normal
   Built with C_OBJECTS_OLD_GAUGE it is another plugin, "cobjold", with one node type,
   cobjold.gauge, that offers "cobj.gauge" at version 1 only: a producer too old for cobj.read_gauge,
   which the host refuses at scene load. */
#include <mechgraph/c/domain/cam_law.h>
#include <mechgraph/c/domain/fit.h>
#include <mechgraph/c/node.h>
#include <mechgraph/c/plugin.h>

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

static const mg_eval_suite_v1* eval;
static atomic_long live_objects;

typedef struct law {
  mg_object base; /* first: mg_object* <-> law* */
  atomic_int refs;
  double lift, half_width;
} law;

static const law* as_law(const mg_object* o) { return (const law*)(const void*)o; }

static void law_retain(const mg_object* o) { atomic_fetch_add(&((law*)(void*)o)->refs, 1); }
static void law_release(const mg_object* o) {
  law* l = (law*)(void*)o;
  if (atomic_fetch_sub(&l->refs, 1) == 1) {
    free(l);
    atomic_fetch_sub(&live_objects, 1);
  }
}
static void law_event(const mg_object* o, double* begin, double* end) {
  *begin = -as_law(o)->half_width;
  *end = as_law(o)->half_width;
}
static mg_status law_evaluate(const mg_object* o, double phi, mg_lift4* out) {
  const double k = 3.14159265358979323846 / (2.0 * as_law(o)->half_width), h = as_law(o)->lift;
  const double c = cos(k * phi), s = sin(k * phi);
  out->h = h * c * c;
  out->dh = -2.0 * h * k * c * s;
  out->d2h = -2.0 * h * k * k * (c * c - s * s);
  out->d3h = 8.0 * h * k * k * k * c * s;
  return MG_OK;
}
static mg_status law_evaluate_many(const mg_object* o, const double* phi, size_t n, mg_lift4* out) {
  size_t i;
  for (i = 0; i < n; ++i) law_evaluate(o, phi[i], out + i);
  return MG_OK;
}
static size_t law_breakpoints(const mg_object* o, double* out, size_t capacity) {
  (void)o;
  (void)out;
  (void)capacity;
  return 0;
}
static double law_max_lift(const mg_object* o) { return as_law(o)->lift; }
static double law_base_radius(const mg_object* o) {
  (void)o;
  return 0.02;
}
static double law_roller_radius(const mg_object* o) {
  (void)o;
  return 0.0;
}
static const mg_cam_law_v1 law_table = {sizeof(mg_cam_law_v1), law_event,    law_evaluate,     law_evaluate_many,
                                        law_breakpoints,       law_max_lift, law_base_radius, law_roller_radius};
static const void* law_query(const mg_object* o, const char* name, uint32_t version) {
  (void)o;
  return strcmp(name, MG_CAM_LAW) == 0 && version == 1 ? &law_table : NULL;
}
static const char* law_maker(const mg_object* o) {
  (void)o;
  return "cobj.law";
}
static const char origin = 0;
static const mg_object_vtbl law_vtbl = {sizeof(mg_object_vtbl), law_retain, law_release, law_query, law_maker, &origin};

/* The private interface "cobj.gauge": version 1 reads a number; version 2 (the same table here)
   is what cobj.read_gauge asks for. */
#ifdef C_OBJECTS_OLD_GAUGE
#define GAUGE_VERSION 1u
#define PLUGIN_ID "cobjold"
#else
#define GAUGE_VERSION 2u
#define PLUGIN_ID "cobj"
#endif
typedef struct gauge_v1 {
  uint32_t struct_size;
  double (*reading)(const mg_object* self);
} gauge_v1;

typedef struct gauge {
  mg_object base;
  atomic_int refs;
  double reading;
} gauge;

static void gauge_retain(const mg_object* o) { atomic_fetch_add(&((gauge*)(void*)o)->refs, 1); }
static void gauge_release(const mg_object* o) {
  gauge* g = (gauge*)(void*)o;
  if (atomic_fetch_sub(&g->refs, 1) == 1) {
    free(g);
    atomic_fetch_sub(&live_objects, 1);
  }
}
static double gauge_reading(const mg_object* o) { return ((const gauge*)(const void*)o)->reading; }
static const gauge_v1 gauge_table = {sizeof(gauge_v1), gauge_reading};
static const void* gauge_query(const mg_object* o, const char* name, uint32_t version) {
  (void)o;
  return strcmp(name, "cobj.gauge") == 0 && version >= 1 && version <= GAUGE_VERSION ? &gauge_table : NULL;
}
static const char* gauge_maker(const mg_object* o) {
  (void)o;
  return PLUGIN_ID ".gauge";
}
static const mg_object_vtbl gauge_vtbl = {sizeof(mg_object_vtbl), gauge_retain, gauge_release, gauge_query, gauge_maker, &origin};

/* mechgraph.fit/1: plain data that lives as long as the object (here: static). */
typedef struct fit {
  mg_object base;
  atomic_int refs;
} fit;
static void fit_retain(const mg_object* o) { atomic_fetch_add(&((fit*)(void*)o)->refs, 1); }
static void fit_release(const mg_object* o) {
  fit* f = (fit*)(void*)o;
  if (atomic_fetch_sub(&f->refs, 1) == 1) {
    free(f);
    atomic_fetch_sub(&live_objects, 1);
  }
}
static void fit_data(const mg_object* o, mg_fit_data_v1* out) {
  (void)o;
  out->designation = "20 c-fit";
  out->nominal = 0.020;
  out->hole.upper = 21e-6;
  out->hole.lower = 0.0;
  out->shaft.upper = -7e-6;
  out->shaft.lower = -20e-6;
  out->hole_distribution = MG_DISTRIBUTION_UNIFORM;
  out->shaft_distribution = MG_DISTRIBUTION_NORMAL;
}
static const mg_fit_v1 fit_table = {sizeof(mg_fit_v1), fit_data};
static const void* fit_query(const mg_object* o, const char* name, uint32_t version) {
  (void)o;
  return version == 1 && strcmp(name, MG_FIT) == 0 ? &fit_table : NULL;
}
static const char* fit_maker(const mg_object* o) {
  (void)o;
  return PLUGIN_ID ".fit";
}
static const mg_object_vtbl fit_vtbl = {sizeof(mg_object_vtbl), fit_retain, fit_release, fit_query, fit_maker, &origin};

static mg_str str(const char* s) {
  mg_str out;
  out.data = s;
  out.size = strlen(s);
  return out;
}

static mg_status make_law(const mg_node_type* self, const mg_eval_args* args, mg_eval_ctx* ctx) {
  law* l = (law*)malloc(sizeof(law));
  (void)self;
  if (!l) return MG_ERR_NO_MEMORY;
  l->base.vtbl = &law_vtbl;
  atomic_init(&l->refs, 1);
  l->lift = args->params[0].number;
  l->half_width = args->params[1].number * (args->params[2].number != 0.0 ? 4.0 : 1.0);
  atomic_fetch_add(&live_objects, 1);
  return eval->set_object(ctx, 0, &l->base); /* hands over its one reference */
}

static mg_status peak(const mg_node_type* self, const mg_eval_args* args, mg_eval_ctx* ctx) {
  const mg_object* o;
  const mg_cam_law_v1* t;
  mg_lift4 d;
  (void)self;
  if (args->inputs[0].count != 1 || args->inputs[0].values[0].kind != MG_VALUE_OBJECT) {
    eval->fail(ctx, str("law"), str("needs one cam law"));
    return MG_ERR_NODE;
  }
  o = args->inputs[0].values[0].u.object;
  t = (const mg_cam_law_v1*)o->vtbl->query(o, MG_CAM_LAW, 1);
  if (!t) return MG_ERR_MISSING_FEATURE;
  if (t->evaluate(o, 0.0, &d) != MG_OK) return MG_ERR_INTERNAL;
  eval->set_scalar(ctx, 0, d.h);
  return MG_OK;
}

static mg_status make_gauge(const mg_node_type* self, const mg_eval_args* args, mg_eval_ctx* ctx) {
  gauge* g = (gauge*)malloc(sizeof(gauge));
  (void)self;
  (void)args;
  if (!g) return MG_ERR_NO_MEMORY;
  g->base.vtbl = &gauge_vtbl;
  atomic_init(&g->refs, 1);
  g->reading = 42.0;
  atomic_fetch_add(&live_objects, 1);
  return eval->set_object(ctx, 0, &g->base);
}

static mg_status read_gauge(const mg_node_type* self, const mg_eval_args* args, mg_eval_ctx* ctx) {
  const mg_object* o;
  const gauge_v1* t;
  (void)self;
  if (args->inputs[0].count != 1 || args->inputs[0].values[0].kind != MG_VALUE_OBJECT) return MG_ERR_BAD_ARGUMENT;
  o = args->inputs[0].values[0].u.object;
  t = (const gauge_v1*)o->vtbl->query(o, "cobj.gauge", GAUGE_VERSION);
  if (!t) {
    eval->fail(ctx, str("gauge"), str("the gauge does not answer cobj.gauge version 2"));
    return MG_ERR_MISSING_FEATURE;
  }
  eval->set_scalar(ctx, 0, t->reading(o));
  return MG_OK;
}

static mg_status make_fit(const mg_node_type* self, const mg_eval_args* args, mg_eval_ctx* ctx) {
  fit* f = (fit*)malloc(sizeof(fit));
  (void)self;
  (void)args;
  if (!f) return MG_ERR_NO_MEMORY;
  f->base.vtbl = &fit_vtbl;
  atomic_init(&f->refs, 1);
  atomic_fetch_add(&live_objects, 1);
  return eval->set_object(ctx, 0, &f->base);
}

static mg_status live(const mg_node_type* self, const mg_eval_args* args, mg_eval_ctx* ctx) {
  (void)self;
  (void)args;
  eval->set_scalar(ctx, 0, (double)atomic_load(&live_objects));
  return MG_OK;
}

#define NONE {0, 0, 0, 0, 0, 0, 0, 0}
#define LENGTH {1, 0, 0, 0, 0, 0, 0, 0}
#define ANGLE {0, 0, 0, 1, 0, 0, 0, 0}

static mg_param_decl law_params[3];
static const mg_port_decl law_out[1] = {{sizeof(mg_port_decl), "law", MG_VALUE_OBJECT, NONE, "the cam law", MG_CAM_LAW, 1, 0,
                                         NULL, NULL, MG_NO_FRAME, NULL}};
static const mg_port_decl peak_in[1] = {{sizeof(mg_port_decl), "law", MG_VALUE_OBJECT, NONE, "a cam law", MG_CAM_LAW, 1, 0,
                                         NULL, NULL, MG_NO_FRAME, NULL}};
static const mg_port_decl peak_out[1] = {{sizeof(mg_port_decl), "lift", MG_VALUE_SCALAR, LENGTH, "lift at the nose", NULL, 0,
                                          0, "mm", NULL, MG_NO_FRAME, NULL}};
static const mg_port_decl live_out[1] = {{sizeof(mg_port_decl), "count", MG_VALUE_SCALAR, NONE, "objects alive", NULL, 0, 0,
                                          NULL, NULL, MG_NO_FRAME, NULL}};
static const mg_port_decl gauge_out[1] = {{sizeof(mg_port_decl), "gauge", MG_VALUE_OBJECT, NONE, "a gauge", "cobj.gauge",
                                           GAUGE_VERSION, 0, NULL, NULL, MG_NO_FRAME, NULL}};
static const mg_port_decl read_gauge_in[1] = {{sizeof(mg_port_decl), "gauge", MG_VALUE_OBJECT, NONE, "a gauge", "cobj.gauge",
                                              GAUGE_VERSION, 0, NULL, NULL, MG_NO_FRAME, NULL}};
static const mg_port_decl read_gauge_out[1] = {{sizeof(mg_port_decl), "reading", MG_VALUE_SCALAR, NONE, "the gauge's reading",
                                               NULL, 0, 0, NULL, NULL, MG_NO_FRAME, NULL}};
static const mg_port_decl fit_out[1] = {{sizeof(mg_port_decl), "fit", MG_VALUE_OBJECT, NONE, "a fit", MG_FIT, 1, 0, NULL,
                                         NULL, MG_NO_FRAME, NULL}};
static mg_node_desc descs[6];
static mg_node_type node_types[6];
static const mg_node_type* type_list[6] = {&node_types[0], &node_types[1], &node_types[2],
                                           &node_types[3], &node_types[4], &node_types[5]};
static mg_plugin plugin;

static void number(mg_param_decl* p, const char* name, mg_dim dim, const char* doc, double fallback) {
  memset(p, 0, sizeof *p);
  p->struct_size = sizeof *p;
  p->name = name;
  p->kind = MG_PARAM_NUMBER;
  p->dim = dim;
  p->doc = doc;
  p->flags = MG_PF_REQUIRED | MG_PF_HAS_DEFAULT;
  p->min = 0.0;
  p->max = 10.0;
  p->default_value.kind = MG_PARAM_NUMBER;
  p->default_value.present = 1;
  p->default_value.number = fallback;
  p->angle_frame = MG_NO_FRAME;
}

static void node(int i, const char* type, const char* summary, const mg_param_decl* params, size_t param_count,
                 const mg_port_decl* inputs, size_t input_count, const mg_port_decl* outputs, mg_status (*f)(const mg_node_type*, const mg_eval_args*, mg_eval_ctx*)) {
  memset(&descs[i], 0, sizeof descs[i]);
  descs[i].struct_size = sizeof descs[i];
  descs[i].type = type;
  descs[i].version = 1;
  descs[i].summary = summary;
  descs[i].params = params;
  descs[i].param_count = param_count;
  descs[i].inputs = inputs;
  descs[i].input_count = input_count;
  descs[i].outputs = outputs;
  descs[i].output_count = 1;
  memset(&node_types[i], 0, sizeof node_types[i]);
  node_types[i].struct_size = sizeof node_types[i];
  node_types[i].desc = &descs[i];
  node_types[i].evaluate = f;
}

const mg_plugin* mechgraph_plugin_entry_1(const mg_host* host, mg_text_sink why) {
  memset(&plugin, 0, sizeof plugin);
  eval = (const mg_eval_suite_v1*)host->fetch(host->host_data, MG_SUITE_EVAL, 1);
  if (!eval) {
    why.append(why.self, "no eval suite", 13);
    return NULL;
  }
  {
    const mg_dim length = LENGTH, angle = ANGLE, none = NONE;
    number(&law_params[0], "lift", length, "the largest lift", 0.008);
    number(&law_params[1], "half_width", angle, "half the event", 1.0);
    number(&law_params[2], "wide", none, "1: an event four times as wide (beyond +-180 deg)", 0.0);
  }
#ifdef C_OBJECTS_OLD_GAUGE
  node(0, "cobjold.gauge", "a gauge of the interface's first version", NULL, 0, NULL, 0, gauge_out, make_gauge);
  plugin.node_type_count = 1;
  (void)make_law, (void)peak, (void)live, (void)read_gauge, (void)law_out, (void)peak_in, (void)peak_out, (void)live_out;
  (void)read_gauge_in, (void)read_gauge_out, (void)make_fit, (void)fit_out;
#else
  node(0, "cobj.law", "a cosine-squared cam law (a C object)", law_params, 3, NULL, 0, law_out, make_law);
  node(1, "cobj.peak", "the lift of a cam law at the nose", NULL, 0, peak_in, 1, peak_out, peak);
  node(2, "cobj.live", "how many objects of this plugin are alive", NULL, 0, NULL, 0, live_out, live);
  node(3, "cobj.gauge", "a gauge (a private interface at version 2)", NULL, 0, NULL, 0, gauge_out, make_gauge);
  node(4, "cobj.read_gauge", "the reading of a gauge of version 2 or later", NULL, 0, read_gauge_in, 1, read_gauge_out, read_gauge);
  node(5, "cobj.fit", "a fit (a C object of mechgraph.fit, SDK 1.1)", NULL, 0, NULL, 0, fit_out, make_fit);
  plugin.node_type_count = 6;
#endif
  plugin.struct_size = sizeof plugin;
  plugin.sdk_major = MG_SDK_MAJOR;
  plugin.sdk_minor = MG_SDK_MINOR;
  plugin.plugin_id = PLUGIN_ID;
  plugin.plugin_version = "1.0.0";
  plugin.node_types = type_list;
  return &plugin;
}
