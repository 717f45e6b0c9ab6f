/* Objects of the SDK interfaces written in C, each breaking one point of its contract (or none),
   for mg_check_object (tests/sdk/object_contracts_test.cpp). Not a plugin: the test opens it and
   asks broken_contracts_object(which) for an object, then checks it with libmechgraph_sdk's
   mg_check_object. `which`: 0-19 valve motions, 20-29 followers, 30-39 joint plays (the table in
   the test says what each breaks); 0, 20 and 30 keep their contract. Objects are static: retain
   and release do nothing. */
#include <mechgraph/c/domain/cam_law.h>
#include <mechgraph/c/domain/follower.h>
#include <mechgraph/c/domain/joint_play.h>
#include <mechgraph/c/domain/valve_motion.h>

#include <math.h>
#include <string.h>

typedef struct broken {
  mg_object base;
  int which;
} broken;

static int which_of(const mg_object* o) { return ((const broken*)o)->which; }

static void no_op(const mg_object* self) { (void)self; }
static const char* maker(const mg_object* self) {
  (void)self;
  return "broken_contracts";
}

/* The cam a valve motion follows: it only needs to answer mechgraph.cam_law/1 here. */
static const mg_cam_law_v1 cam_table = {.struct_size = sizeof(mg_cam_law_v1)};
static const void* cam_query(const mg_object* self, const char* name, uint32_t version) {
  (void)self;
  return strcmp(name, MG_CAM_LAW) == 0 && version == 1 ? &cam_table : NULL;
}
static const mg_object_vtbl cam_vtbl = {sizeof(mg_object_vtbl), no_op, no_op, cam_query, maker, NULL};
static const mg_object cam = {&cam_vtbl};

/* Valve motion: x = 4 mm sin^2 over the open period (-1, 1) rad, knots -1, 0, 1. */
static mg_status vm_at(const mg_object* self, double phi, mg_lift4* out) {
  const double s = sin(1.5707963267948966 * (phi + 1.0));
  out->h = 0.004 * s * s;
  out->dh = out->d2h = out->d3h = 0.0;
  if (which_of(self) == 9 && phi > 0.5) out->h = NAN;
  if (which_of(self) == 10) out->h = -0.001;
  return MG_OK;
}
static mg_status vm_at_many(const mg_object* self, const double* phi, size_t n, mg_lift4* out) {
  for (size_t i = 0; i < n; ++i) vm_at(self, phi[i], &out[i]);
  return MG_OK;
}
static double vm_speed(const mg_object* self) { return which_of(self) == 2 ? 0.0 : 300.0; }
static void vm_open(const mg_object* self, double* begin, double* end) {
  *begin = -1.0;
  *end = which_of(self) == 5 ? -1.0 : 1.0;
}
static size_t vm_knots(const mg_object* self, double* out, size_t capacity) {
  double k[3] = {-1.0, 0.0, 1.0};
  if (which_of(self) == 6) k[0] = -0.9;
  if (which_of(self) == 7) k[1] = 1.0;
  if (which_of(self) == 5) k[1] = k[2] = -1.0;
  for (size_t i = 0; i < 3 && i < capacity; ++i) out[i] = k[i];
  return 3;
}
static double vm_ratio(const mg_object* self) { return which_of(self) == 3 ? NAN : 1.5; }
static double vm_lash(const mg_object* self) { return which_of(self) == 4 ? -0.0001 : 0.0002; }
static const mg_object* vm_cam(const mg_object* self) { return which_of(self) == 8 ? NULL : &cam; }
static const mg_valve_motion_v1 vm_table = {sizeof(mg_valve_motion_v1), vm_at, vm_at_many, vm_speed, vm_open,
                                            vm_knots, vm_ratio, vm_lash, vm_cam};
static const mg_valve_motion_v1 vm_incomplete = {sizeof(mg_valve_motion_v1), vm_at, NULL, vm_speed, vm_open,
                                                 vm_knots, vm_ratio, vm_lash, vm_cam};

/* Follower: a translating roller of 8 mm. */
static void f_type_name(const mg_object* self, mg_text_sink out) {
  if (which_of(self) != 22) out.append(out.self, "broken.roller", 13);
}
static void f_describe(const mg_object* self, mg_text_sink out) {
  (void)self;
  out.append(out.self, "roller 8 mm", 11);
}
static double f_roller(const mg_object* self) { return which_of(self) == 23 ? -0.004 : 0.004; }
static int32_t f_pivoted(const mg_object* self) { return which_of(self) == 24 ? 2 : 0; }
static double f_lever(const mg_object* self, double base_radius) {
  (void)self;
  (void)base_radius;
  return 0.0;
}
static mg_status f_contact(const mg_object* self, double phi, const mg_lift4* lift, double base_radius,
                           int32_t clockwise, mg_follower_contact* out, const mg_error* err) {
  (void)self, (void)phi, (void)lift, (void)base_radius, (void)clockwise, (void)err;
  memset(out, 0, sizeof *out);
  return MG_OK;
}
static const mg_follower_v1 f_table = {sizeof(mg_follower_v1), f_type_name, f_describe, f_roller, f_pivoted,
                                       f_lever, f_contact};
static const mg_follower_v1 f_incomplete = {sizeof(mg_follower_v1), f_type_name, f_describe, f_roller, f_pivoted,
                                            f_lever, NULL};

/* Joint play: a pin in a hole, one term of two links. */
static void jp_data(const mg_object* self, mg_joint_play_data_v1* out) {
  static mg_tolerance_link links[40][2];
  static mg_play_term terms[40][1];
  const int w = which_of(self);
  mg_tolerance_link* l = links[w];
  l[0] = (mg_tolerance_link){"hole", 0.010025, 0.000025, 1.0, MG_DISTRIBUTION_NORMAL, 0};
  l[1] = (mg_tolerance_link){"pin", 0.009975, 0.000025, -1.0, MG_DISTRIBUTION_UNIFORM, 0};
  if (w == 34) l[1].half_range = -0.000025;
  if (w == 35) l[0].mean = NAN;
  if (w == 36) l[1].distribution = 7;
  if (w == 37) l[1].label = NULL;
  terms[w][0] = (mg_play_term){"radial", l, 2};
  out->joint = w == 32 ? "" : "pin_in_hole";
  out->terms = terms[w];
  out->term_count = w == 33 ? 0 : 1;
}
static const mg_joint_play_v1 jp_table = {sizeof(mg_joint_play_v1), jp_data};
static const mg_joint_play_v1 jp_incomplete = {sizeof(mg_joint_play_v1), NULL};

static const void* query(const mg_object* self, const char* name, uint32_t version) {
  const int w = which_of(self);
  if (version != 1) return NULL;
  if (w < 20 && strcmp(name, MG_VALVE_MOTION) == 0) return w == 1 ? &vm_incomplete : &vm_table;
  if (w >= 20 && w < 30 && strcmp(name, MG_FOLLOWER) == 0) return w == 21 ? &f_incomplete : &f_table;
  if (w >= 30 && w < 40 && strcmp(name, MG_JOINT_PLAY) == 0) return w == 31 ? &jp_incomplete : &jp_table;
  return NULL;
}
static const mg_object_vtbl vtbl = {sizeof(mg_object_vtbl), no_op, no_op, query, maker, NULL};

__attribute__((visibility("default"))) const mg_object* broken_contracts_object(int which) {
  static broken objects[40];
  if (which < 0 || which >= 40) return NULL;
  objects[which].base.vtbl = &vtbl;
  objects[which].which = which;
  return &objects[which].base;
}
