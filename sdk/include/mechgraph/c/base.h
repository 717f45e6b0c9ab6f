/* mechgraph SDK 1.x, the binary boundary: base types (docs/design/sdk-1.0.md, section 1.2).
 *
 * Everything that crosses between the host and a plugin, or between two plugins, is declared in
 * these C11 headers: function tables, plain structs, opaque handles, int32_t statuses. No C++
 * type, exception or allocator crosses. The rules for every type in sdk/include/mechgraph/c:
 *  - Linux on LP64 (x86_64, aarch64), the default calling convention.
 *  - No C enum in a struct (int32_t plus #defines: -fshort-enums cannot change a layout), no bool
 *    (int32_t), no bit-fields, no long double.
 *  - A struct that may grow starts with `uint32_t struct_size`, which its writer sets to
 *    sizeof(the struct) as it was compiled. Later 1.x minors only append fields; a reader reads a
 *    field only when MG_HAS_FIELD says the writer's struct holds it, else takes the documented
 *    default. An array of such structs is strided by its elements' struct_size (MG_ELEMENT), never
 *    by the reader's sizeof, so an older plugin's arrays are read right.
 *  - A struct without struct_size (mg_dim, mg_str, mg_column, mg_code ...) is frozen forever; a
 *    field more would be a new struct.
 *  - Function tables (suites, interfaces) are frozen once shipped: change is a new name or version.
 *  - Descriptions: UTF-8, NUL-terminated. Run-time text: (pointer, size), not NUL-terminated.
 */
#ifndef MECHGRAPH_C_BASE_H
#define MECHGRAPH_C_BASE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
#define MG_EXTERN_C_BEGIN extern "C" {
#define MG_EXTERN_C_END }
#define MG_EXTERN_C extern "C"
#else
#define MG_EXTERN_C_BEGIN
#define MG_EXTERN_C_END
#define MG_EXTERN_C
#endif

/* A function of libmechgraph_sdk.so.1 (sdk_lib.h). */
#define MG_API MG_EXTERN_C __attribute__((visibility("default")))
/* The one function a plugin exports (plugin.h). */
#define MG_PLUGIN_EXPORT MG_EXTERN_C __attribute__((visibility("default")))

MG_EXTERN_C_BEGIN

/* The SDK these headers describe. A plugin records the numbers it was compiled with (mg_plugin);
   a host loads it when the major is equal and the plugin's minor is not above its own. */
#define MG_SDK_MAJOR 1
#define MG_SDK_MINOR 5

/* Statuses (OpenFX's kOfxStat*, FMI's graded status). Readers treat an unknown code as
   MG_ERR_INTERNAL. */
typedef int32_t mg_status;
#define MG_OK                  0
#define MG_ERR_NODE            1 /* infeasible parameter/input; fail() named it first            */
#define MG_ERR_CANCELLED       2 /* the host's cancellation was honoured                         */
#define MG_ERR_NO_MEMORY       3
#define MG_ERR_UNSUPPORTED     4 /* an optional query this object cannot answer (closed forms)   */
#define MG_ERR_BAD_ARGUMENT    5 /* the caller broke the contract (phi outside the event ...)    */
#define MG_ERR_MISSING_FEATURE 6 /* a needed suite or interface is absent                        */
#define MG_ERR_INTERNAL        7 /* a defect: an exception caught at the boundary, a NaN ...     */

/* Exponents of a physical dimension over SI base quantities, plus plane angle kept as a base.
   The first five are mechgraph::Dimension's, in its order; all eight are named now, so the struct
   never grows. */
typedef struct mg_dim {
  int8_t length, mass, time, angle, temperature, current, amount, luminous;
} mg_dim;

/* Borrowed text, not NUL-terminated; valid for the call it is passed in. */
typedef struct mg_str {
  const char* data;
  size_t size;
} mg_str;

/* Text flows into the receiver's buffer: nothing is allocated on one side and freed on the other.
   append may be called several times; `self` is the receiver's. */
typedef struct mg_text_sink {
  void* self;
  void (*append)(void* self, const char* text, size_t size);
} mg_text_sink;

/* What a consumer gives a producer to describe a failure (FMI's logger, per call). */
typedef struct mg_error {
  uint32_t struct_size;
  mg_text_sink parameter; /* the parameter or input at fault ("base_radius"); may stay empty */
  mg_text_sink message;
} mg_error;

/* Ownership of a buffer handed over (DLPack's deleter): release(ctx) is called exactly once, from
   any thread, when the receiver is done. release == NULL: static storage, nothing to free. */
typedef struct mg_owner {
  void* ctx;
  void (*release)(void* ctx);
} mg_owner;

/* Whether the writer's struct (its struct_size) holds `field`, a field of `type`. */
#define MG_HAS_FIELD(ptr, type, field) \
  ((ptr)->struct_size >= offsetof(type, field) + sizeof(((type*)0)->field))

/* Element `index` of an array of growable structs: strided by the elements' own struct_size (all
   elements of one array have the writer's size). */
#define MG_ELEMENT(type, array, index) \
  ((const type*)(const void*)((const char*)(array) + (size_t)(index) * (size_t)(array)->struct_size))

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_BASE_H */
