/* mechgraph SDK 1.x: values that flow along a graph's edges (docs/design/sdk-1.0.md, section 1.5).
 *
 * Ownership, once for all:
 *  - mg_eval_args, inputs and the mg_values passed in: the host's, valid during evaluate. To keep an
 *    input object longer, retain it.
 *  - An output series or table: the producer's, adopted by the host, which calls owner.release
 *    exactly once.
 *  - An output object: set_object takes over one reference; the last release destroys it, on the
 *    creator's side.
 *  - Text: the receiver's (mg_text_sink); nothing crosses to be freed.
 *  - Arrays a callee fills: the caller's (two calls: the count, then the fill).
 */
#ifndef MECHGRAPH_C_VALUE_H
#define MECHGRAPH_C_VALUE_H

#include <mechgraph/c/base.h>

MG_EXTERN_C_BEGIN

struct mg_object;

#define MG_VALUE_SCALAR 1
#define MG_VALUE_SERIES 2
#define MG_VALUE_TABLE 3
#define MG_VALUE_OBJECT 4

/* One column of a table; `values` has the table's `rows` entries. Frozen. */
typedef struct mg_column {
  const char* name;
  mg_dim dim;
  const char* display_unit; /* "mm"; NULL or "": SI */
  const double* values;
} mg_column;

/* A reference value on the axis (or on the x channel of a curve over a channel), SI. Frozen. */
typedef struct mg_mark {
  const char* label;
  double value;
} mg_mark;

#define MG_TABLE_CLOSED_CURVE 0x1u /* x/y pairs trace closed plane curves in the axis' order */
#define MG_TABLE_HISTOGRAM 0x2u    /* the axis holds bin centres, the channels counts */
#define MG_TABLE_TURNS_CW 0x4u     /* a drawing of a part that turns clockwise (data, not a name) */

typedef struct mg_table {
  uint32_t struct_size;
  size_t rows;
  mg_column axis;
  const mg_column* channels;
  size_t channel_count;
  uint32_t flags; /* MG_TABLE_* */
  const mg_mark* marks;
  size_t mark_count;
  mg_owner owner; /* keeps every pointer above alive until released */
} mg_table;

typedef struct mg_series {
  uint32_t struct_size;
  size_t size;
  const double* axis;
  const double* values;
  mg_dim axis_dim;
  const char* const* labels; /* NULL or `size` entries */
  mg_owner owner;
} mg_series;

typedef struct mg_value {
  int32_t kind; /* MG_VALUE_* */
  uint32_t reserved;
  union {
    double scalar;
    const mg_series* series;
    const mg_table* table;
    const struct mg_object* object;
  } u;
} mg_value;

/* The values connected to one declared input, in connection order (several for a MG_PORT_MULTIPLE
   port, none for an unconnected optional one). */
typedef struct mg_input {
  const mg_value* values;
  size_t count;
} mg_input;

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_VALUE_H */
