/* mechgraph SDK 1.x: the cam law interfaces (docs/design/sdk-1.0.md, section 1.7).
 *
 * A cam law is the lift of the follower over cam angle phi [rad] from the nose, inside its event
 * (begin, end) within (-pi, pi), and zero outside. Tables are frozen: a capability more is a new
 * optional interface queried beside the primary one.
 */
#ifndef MECHGRAPH_C_DOMAIN_CAM_LAW_H
#define MECHGRAPH_C_DOMAIN_CAM_LAW_H

#include <mechgraph/c/object.h>

MG_EXTERN_C_BEGIN

/* Lift and its derivatives over cam angle: m, m/rad, m/rad^2, m/rad^3. Frozen. */
typedef struct mg_lift4 {
  double h, dh, d2h, d3h;
} mg_lift4;

#define MG_CAM_LAW "mechgraph.cam_law" /* version 1 */
typedef struct mg_cam_law_v1 {
  uint32_t struct_size;
  void (*event)(const mg_object* self, double* begin, double* end); /* rad, inside (-pi, pi) */
  /* begin < phi < end; no allocation, thread-safe */
  mg_status (*evaluate)(const mg_object* self, double phi, mg_lift4* out);
  mg_status (*evaluate_many)(const mg_object* self, const double* phi, size_t n, mg_lift4* out);
  /* Two calls: returns the count; fills min(count, capacity) ascending angles strictly inside. */
  size_t (*breakpoints)(const mg_object* self, double* out, size_t capacity);
  double (*max_lift)(const mg_object* self);
  double (*base_radius)(const mg_object* self);
  double (*roller_radius)(const mg_object* self); /* 0: flat face */
} mg_cam_law_v1;

#define MG_CAM_LAW_CLOSED_FORM "mechgraph.cam_law.closed_form" /* version 1, optional */
typedef struct mg_cam_law_closed_form_v1 {
  uint32_t struct_size;
  /* MG_ERR_UNSUPPORTED when this law cannot say for this order (0 lift, 1 velocity, 2 accel.). */
  mg_status (*monotone_breaks)(const mg_object* self, int32_t order, double* out, size_t capacity, size_t* count);
  mg_status (*lift_integrals)(const mg_object* self, double a, double b, double* integral, double* integral_of_square);
} mg_cam_law_closed_form_v1;

#define MG_CAM_LAW_HIGHER "mechgraph.cam_law.higher_derivatives" /* version 1, optional */
typedef struct mg_cam_law_higher_v1 {
  uint32_t struct_size;
  mg_status (*d4_d5)(const mg_object* self, double phi, double* d4, double* d5);
} mg_cam_law_higher_v1;

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_DOMAIN_CAM_LAW_H */
