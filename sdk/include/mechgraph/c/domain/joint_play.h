/* mechgraph SDK 1.x: the joint play interface (docs/design/sdk-1.0.md, section 1.7;
 * docs/methods/backlash.md).
 *
 * A joint's free play along its line of action, as plain data: named terms, each a sum of
 * toleranced links (play = max(0, sum of sensitivity * size)). The data is immutable and lives
 * as long as the object. The structs below are frozen with version 1: a field more is a _v2.
 */
#ifndef MECHGRAPH_C_DOMAIN_JOINT_PLAY_H
#define MECHGRAPH_C_DOMAIN_JOINT_PLAY_H

#include <mechgraph/c/object.h>

MG_EXTERN_C_BEGIN

#define MG_DISTRIBUTION_NORMAL 0     /* the range is 6 sigma */
#define MG_DISTRIBUTION_UNIFORM 1
#define MG_DISTRIBUTION_TRIANGULAR 2 /* symmetric */

typedef struct mg_tolerance_link {
  const char* label;
  double mean;       /* SI */
  double half_range; /* >= 0 */
  double sensitivity;
  int32_t distribution; /* MG_DISTRIBUTION_* */
  uint32_t reserved;
} mg_tolerance_link;

typedef struct mg_play_term {
  const char* label;
  const mg_tolerance_link* links;
  size_t link_count;
} mg_play_term;

typedef struct mg_joint_play_data_v1 {
  const char* joint;
  const mg_play_term* terms;
  size_t term_count;
} mg_joint_play_data_v1;

#define MG_JOINT_PLAY "mechgraph.joint_play" /* version 1 */
typedef struct mg_joint_play_v1 {
  uint32_t struct_size;
  void (*data)(const mg_object* self, mg_joint_play_data_v1* out);
} mg_joint_play_v1;

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_DOMAIN_JOINT_PLAY_H */
