/* mechgraph SDK 1.2: the block form of mechgraph.valve_motion/1 (node_block.h, mg_object_block).
 *
 * A block of valve motions crosses as a structure of arrays, not as one object per case: its
 * `objects` are the cases' cam laws (mechgraph.cam_law/1, each the motion's `cam`; one for every
 * case when object_count is 1), and its `figures` the MG_VALVE_MOTION_BLOCK_FIGURES columns below,
 * in this order. Case i's motion is its cam law at those numbers (valve_motion.h; the open period
 * as the single motion reports it). Frozen with mechgraph.node.block version 1; more figures
 * would come as a new block form, never by changing these.
 */
#ifndef MECHGRAPH_C_DOMAIN_VALVE_MOTION_BLOCK_H
#define MECHGRAPH_C_DOMAIN_VALVE_MOTION_BLOCK_H

#include <mechgraph/c/domain/valve_motion.h>
#include <mechgraph/c/node_block.h>

#define MG_VALVE_MOTION_BLOCK_OPEN_BEGIN 0     /* rad: the cam angle where the valve opens */
#define MG_VALVE_MOTION_BLOCK_OPEN_END 1       /* rad: where it closes */
#define MG_VALVE_MOTION_BLOCK_ROCKER_RATIO 2   /* 1 */
#define MG_VALVE_MOTION_BLOCK_LASH 3           /* m, valve side */
#define MG_VALVE_MOTION_BLOCK_CAMSHAFT_SPEED 4 /* rad/s */
#define MG_VALVE_MOTION_BLOCK_FIGURES 5

#endif /* MECHGRAPH_C_DOMAIN_VALVE_MOTION_BLOCK_H */
