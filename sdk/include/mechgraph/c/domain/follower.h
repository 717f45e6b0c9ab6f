/* mechgraph SDK 1.x: the follower interface (docs/design/sdk-1.0.md, section 1.7;
 * docs/methods/followers.md).
 *
 * What rides on a cam: for the law's lift and derivatives at cam angle phi [rad] and the base
 * radius r0 [m], where it touches the contour, the pressure angle and the contour's radius of
 * curvature there. Frames are those of mechgraph/domain/follower.hpp: the follower on +y over the
 * cam centre, the cam turning counterclockwise seen from the front unless `clockwise`.
 * Immutable and thread-safe. The table and mg_follower_contact are frozen with version 1: a
 * function or a field more is a _v2.
 */
#ifndef MECHGRAPH_C_DOMAIN_FOLLOWER_H
#define MECHGRAPH_C_DOMAIN_FOLLOWER_H

#include <mechgraph/c/domain/cam_law.h>

MG_EXTERN_C_BEGIN

/* Where a follower touches the contour; lengths m, angles rad. Frozen. */
typedef struct mg_follower_contact {
  double x, y;             /* the contact point on the contour, cam frame */
  double pitch_x, pitch_y; /* the roller centre (pitch curve); a flat face: the contact point */
  double pressure_angle;   /* between the contact normal and the follower's motion */
  double curvature_radius; /* of the contour at the contact (negative: concave) */
  double face_position;    /* a flat face: where the contact lies along it */
  double follower_angle;   /* pivoted: the arm's turn from its base-circle position */
} mg_follower_contact;

#define MG_FOLLOWER "mechgraph.follower" /* version 1 */
typedef struct mg_follower_v1 {
  uint32_t struct_size;
  /* The node type that made it ("follower.pivoted_roller") and a short description with its
     dimensions ("roller 8 mm, offset 2 mm"), for messages. */
  void (*type_name)(const mg_object* self, mg_text_sink out);
  void (*describe)(const mg_object* self, mg_text_sink out);
  double (*roller_radius)(const mg_object* self); /* m, 0 for a flat face */
  int32_t (*pivoted)(const mg_object* self);      /* 1 pivoted, 0 translating */
  /* Pivoted: the pivot's distance to the base-circle contact (the arm turns by h / lever);
     0 for a translating follower. */
  double (*cam_lever)(const mg_object* self, double base_radius);
  /* MG_ERR_NODE with err naming the follower's parameter when it cannot sit on that base
     circle; no allocation on success. */
  mg_status (*contact)(const mg_object* self, double phi, const mg_lift4* lift, double base_radius, int32_t clockwise,
                       mg_follower_contact* out, const mg_error* err);
} mg_follower_v1;

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_DOMAIN_FOLLOWER_H */
