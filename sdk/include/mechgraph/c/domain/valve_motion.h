/* mechgraph SDK 1.x: the valve motion interface (docs/design/sdk-1.0.md, section 1.7;
 * docs/methods/valvetrain.md, stage 2).
 *
 * The valve's kinematic motion at one engine speed: valve lift x [m] and its derivatives over cam
 * angle phi [rad] from the nose, zero outside the open period. Immutable and thread-safe.
 */
#ifndef MECHGRAPH_C_DOMAIN_VALVE_MOTION_H
#define MECHGRAPH_C_DOMAIN_VALVE_MOTION_H

#include <mechgraph/c/domain/cam_law.h>

MG_EXTERN_C_BEGIN

#define MG_VALVE_MOTION "mechgraph.valve_motion" /* version 1 */
typedef struct mg_valve_motion_v1 {
  uint32_t struct_size;
  mg_status (*at)(const mg_object* self, double phi, mg_lift4* out);
  mg_status (*at_many)(const mg_object* self, const double* phi, size_t n, mg_lift4* out);
  double (*camshaft_speed)(const mg_object* self); /* rad/s: derivatives over angle to time */
  void (*open_period)(const mg_object* self, double* begin, double* end); /* begin < end */
  /* Two calls: begin, the cam's breakpoints inside, end; ascending. Returns the count. */
  size_t (*knots)(const mg_object* self, double* out, size_t capacity);
  double (*rocker_ratio)(const mg_object* self);
  double (*lash)(const mg_object* self); /* m, valve side */
  /* The cam law it follows: borrowed, valid while this object lives (retain to keep it longer). */
  const mg_object* (*cam)(const mg_object* self);
} mg_valve_motion_v1;

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_DOMAIN_VALVE_MOTION_H */
