/* mechgraph SDK 1.1: the spring interfaces (docs/design/sdk-1.0.md, section 1.7;
 * docs/methods/valvetrain.md, stage 4; the contract of mechgraph/domain/spring.hpp).
 *
 * A spring model (material, geometry rules and limits, not yet sized) sizes a spring for a
 * required line F(x) = preload + rate x on 0 <= x <= stroke; the spring then gives its force,
 * stiffness and stress over the deflection x [m] from the installed length (x = 0 with the valve
 * closed), its masses, surge frequency and the geometry of each coil. Immutable and thread-safe.
 * The tables and the structs below are frozen with version 1: a function or a field more is a _v2.
 */
#ifndef MECHGRAPH_C_DOMAIN_SPRING_H
#define MECHGRAPH_C_DOMAIN_SPRING_H

#include <mechgraph/c/object.h>

MG_EXTERN_C_BEGIN

/* The line a spring must give: F(x) = preload + rate x for 0 <= x <= stroke. Frozen. */
typedef struct mg_spring_line {
  double preload; /* N, force with the valve closed */
  double rate;    /* N/m */
  double stroke;  /* m, full valve lift */
} mg_spring_line;

/* One helical coil of a sized spring; lengths m. Frozen. */
typedef struct mg_coil_geometry {
  double wire_diameter;
  double mean_diameter;
  double active_coils; /* real-valued */
  double total_coils;  /* active plus inactive end coils */
  double solid_length;
  double free_length;
  double rate; /* N/m */
} mg_coil_geometry;

#define MG_SPRING "mechgraph.spring" /* version 1; SDK 1.1 */
typedef struct mg_spring_v1 {
  uint32_t struct_size;
  /* Over the deflection x from the installed length: force N and stiffness dF/dx N/m. Every
     number here is NaN when the spring cannot say. */
  double (*force)(const mg_object* self, double x);
  double (*stiffness)(const mg_object* self, double x);
  double (*stroke)(const mg_object* self);          /* m, the working deflection it was sized for */
  double (*mass)(const mg_object* self);            /* kg, whole spring */
  double (*effective_mass)(const mg_object* self);  /* kg moving with the valve */
  double (*surge_frequency)(const mg_object* self); /* Hz, lowest */
  /* Pa: the highest corrected shear stress over the coils at deflection x, and the allowable. */
  double (*stress)(const mg_object* self, double x);
  double (*allowable_stress)(const mg_object* self);
  /* Writes up to `capacity` coils to `out` (NULL with capacity 0: count only) and returns how many
     there are; a plain spring has one, nested ones more. */
  size_t (*coils)(const mg_object* self, mg_coil_geometry* out, size_t capacity);
} mg_spring_v1;

#define MG_SPRING_MODEL "mechgraph.spring_model" /* version 1; SDK 1.1 */
typedef struct mg_spring_model_v1 {
  uint32_t struct_size;
  /* The node type that made the model ("spring.helical"), for messages. */
  void (*type_name)(const mg_object* self, mg_text_sink out);
  /* A spring that gives `line`: on MG_OK *out is a new reference to an object answering
     mechgraph.spring/1, which the caller releases. MG_ERR_NODE with err naming the model's
     parameter and the limit it broke when no spring can (*out stays NULL). */
  mg_status (*size)(const mg_object* self, const mg_spring_line* line, const mg_object** out, const mg_error* err);
} mg_spring_model_v1;

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_DOMAIN_SPRING_H */
