/* mechgraph SDK 1.1: the fit interface (docs/design/sdk-1.0.md, section 1.7;
 * docs/methods/backlash.md, steps 1-2).
 *
 * A fit between a hole and a shaft of one nominal size, as plain data: each part's limit
 * deviations from the nominal and the distribution its size follows. The clearance is hole minus
 * shaft (S = hole - shaft). The data is immutable and lives as long as the object. The structs
 * below are frozen with version 1: a field more is a _v2.
 */
#ifndef MECHGRAPH_C_DOMAIN_FIT_H
#define MECHGRAPH_C_DOMAIN_FIT_H

#include <mechgraph/c/domain/joint_play.h> /* MG_DISTRIBUTION_* */

MG_EXTERN_C_BEGIN

/* A part's limit deviations from the nominal size, m (ES/EI for a hole, es/ei for a shaft);
   upper >= lower. */
typedef struct mg_limit_pair {
  double upper;
  double lower;
} mg_limit_pair;

typedef struct mg_fit_data_v1 {
  const char* designation; /* "20 H11/d11" or "20 explicit"; names the clearance term */
  double nominal;          /* m, > 0 */
  mg_limit_pair hole;
  mg_limit_pair shaft;
  int32_t hole_distribution;  /* MG_DISTRIBUTION_* */
  int32_t shaft_distribution; /* MG_DISTRIBUTION_* */
} mg_fit_data_v1;

#define MG_FIT "mechgraph.fit" /* version 1; SDK 1.1 */
typedef struct mg_fit_v1 {
  uint32_t struct_size;
  void (*data)(const mg_object* self, mg_fit_data_v1* out);
} mg_fit_v1;

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_DOMAIN_FIT_H */
