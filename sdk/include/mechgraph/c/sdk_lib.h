/* mechgraph SDK 1.x: the functions libmechgraph_sdk.so.1 exports (docs/design/sdk-1.0.md,
 * sections 1.7 and 3.6). They are the SDK's ABI, checked with abidiff against the tagged release.
 * Rule: an SDK function never keeps its arguments after it returns.
 */
#ifndef MECHGRAPH_C_SDK_LIB_H
#define MECHGRAPH_C_SDK_LIB_H

#include <mechgraph/c/base.h>
#include <mechgraph/c/domain/cam_law.h>
#include <mechgraph/c/domain/fit.h>
#include <mechgraph/c/domain/follower.h>
#include <mechgraph/c/domain/joint_play.h>
#include <mechgraph/c/domain/spring.h>
#include <mechgraph/c/domain/valve_motion.h>
#include <mechgraph/c/domain/valve_motion_block.h>
#include <mechgraph/c/host.h>
#include <mechgraph/c/node.h>
#include <mechgraph/c/node_block.h>
#include <mechgraph/c/node_cxx.h>
#include <mechgraph/c/node_forecast.h>
#include <mechgraph/c/node_forecast_reads.h>
#include <mechgraph/c/object.h>
#include <mechgraph/c/object_cxx.h>
#include <mechgraph/c/plugin.h>
#include <mechgraph/c/present.h>
#include <mechgraph/c/value.h>

MG_EXTERN_C_BEGIN

/* The SDK the library implements: MG_SDK_MAJOR and its own minor (>= the headers' a plugin was
   built with, when the library is the newer one). Either pointer may be NULL. */
MG_API void mg_sdk_version(uint16_t* major, uint16_t* minor);

/* The name of a status ("MG_ERR_NODE"); "MG_ERR_INTERNAL" for an unknown code (the rule of base.h).
   Static storage. */
MG_API const char* mg_status_name(mg_status status);

/* Checks that `object` keeps the contract of interface `name` at `version` for every SDK interface
   it knows (a cam law: its event inside (-pi, pi), ascending breakpoints strictly inside, finite
   lift and derivatives at samples and at every piece's middle; no lift beyond max_lift. A valve
   motion: its table complete, camshaft speed and rocker ratio positive, lash not negative, the
   open period not empty, the knots ascending from its begin to its end, a cam law, the lift finite
   and not negative at samples and in every piece. A follower: its table complete, a type name, a
   roller radius not negative, `pivoted` 0 or 1. A joint play: its table complete, the joint named,
   terms and links labelled, each link finite with a half range not negative and a known
   distribution; the text names the term and link). Returns
   MG_OK when it does or when the interface is not the SDK's (a plugin's private one), else
   MG_ERR_BAD_ARGUMENT with what it breaks in `problem`, or MG_ERR_MISSING_FEATURE when the object
   does not answer `name`/`version`. */
MG_API mg_status mg_check_object(const mg_object* object, const char* name, uint32_t version, mg_text_sink problem);

/* Does nothing. It names every public struct of SDK 1.0 (the others are reachable from these),
   so that abidw, which sees only the types reachable from exported functions, puts every one of
   them in the ABI dump (scripts/abi-dump.sh) and abidiff compares them with the sdk-1.0 release
   (scripts/test-sdk-compat.sh). Frozen like every function here: a later minor that adds a
   struct or an interface table adds its own anchor, mg_abi_anchor_1_<minor>. */
MG_API void mg_abi_anchor(const mg_host* host, const mg_plugin* plugin, const mg_log_suite_v1* log,
                          const mg_eval_suite_v1* eval, const mg_memory_suite_v1* memory,
                          const mg_node_type* node_type, const mg_eval_args* args, const mg_error* error,
                          const mg_series* series, const mg_table* table, const mg_value* value,
                          const mg_object* object, const mg_cam_law_v1* cam_law,
                          const mg_cam_law_closed_form_v1* closed_form, const mg_cam_law_higher_v1* higher,
                          const mg_valve_motion_v1* valve_motion, const mg_joint_play_v1* joint_play,
                          const mg_follower_v1* follower, const mg_owner* owner);

/* SDK 1.1: does nothing; names the structs 1.1 added (node_forecast.h, domain/fit.h,
   domain/spring.h), as mg_abi_anchor does for 1.0's. */
MG_API void mg_abi_anchor_1_1(const mg_node_forecast_v1* node_forecast, const mg_work_forecast* work_forecast,
                              const mg_fit_v1* fit, const mg_spring_model_v1* spring_model, const mg_spring_v1* spring);

/* SDK 1.2: does nothing; names the structs 1.2 added (node_block.h), as mg_abi_anchor does for
   1.0's. */
MG_API void mg_abi_anchor_1_2(const mg_node_block_v1* node_block, const mg_block_args* block_args,
                              const mg_block_request* block_request, const mg_block_host_v1* block_host,
                              const mg_object_block* object_block, const mg_block_input* block_input,
                              const mg_block_column* block_column);

/* SDK 1.3: does nothing; names the struct 1.3 added (node_forecast_reads.h), as mg_abi_anchor does
   for 1.0's. */
MG_API void mg_abi_anchor_1_3(const mg_node_forecast_reads_v1* node_forecast_reads);

/* SDK 1.4: does nothing; names the struct 1.4 added (object_cxx.h), as mg_abi_anchor does for
   1.0's. */
MG_API void mg_abi_anchor_1_4(const mg_object_cxx_v1* object_cxx);

/* SDK 1.5: does nothing; names the struct 1.5 added (node_cxx.h), as mg_abi_anchor does for
   1.0's. */
MG_API void mg_abi_anchor_1_5(const mg_node_cxx_v1* node_cxx);

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_SDK_LIB_H */
