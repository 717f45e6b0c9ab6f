/* mechgraph SDK 1.x: presentation declarations (docs/design/sdk-1.0.md, section 1.6).
 *
 * Ports declare what a host needs to present them, so that the host never guesses from names: a
 * role (how a table is drawn), channels with labels, units, angle frames and named codes, points
 * another port puts on a figure, and the notes a node makes. A host draws and converts from these
 * declarations only. Unknown roles are drawn as MG_ROLE_PLAIN; unknown flags are ignored.
 */
#ifndef MECHGRAPH_C_PRESENT_H
#define MECHGRAPH_C_PRESENT_H

#include <mechgraph/c/base.h>

MG_EXTERN_C_BEGIN

/* A reference to frame `index` of mg_node_desc::frames, as angle_frame and base_frame fields hold it:
   the index plus one, so that 0, what a zeroed struct holds, means "no frame". */
#define MG_FRAME(index) ((int32_t)(index) + 1)
#define MG_NO_FRAME 0

#define MG_ROLE_PLAIN 0              /* each channel over the axis, compared across nodes */
#define MG_ROLE_DERIVATIVE_FAMILY 1  /* channels are f, f', f'', ... over the axis: a stacked panel */
#define MG_ROLE_CURVE_OVER_CHANNEL 2 /* channels drawn over x_channel, not over the axis */
#define MG_ROLE_DRAWING_TO_SCALE 3   /* x/y pairs, equal scales, DXF layers */
#define MG_ROLE_EVENTS 4             /* few rows: printed as rows; code channels shown by name */
#define MG_ROLE_HISTOGRAM 5

#define MG_CH_ALT_AXIS 0x01u       /* another scale of the axis: not drawn as a curve */
#define MG_CH_CURVATURE 0x02u      /* a radius of curvature: drawn as 1/rho on its own figure */
#define MG_CH_POSITIVE_ONLY 0x04u  /* drawn only where > 0 */
#define MG_CH_NOT_DRAWN 0x08u      /* in CSV/JSON, not in figures */
#define MG_CH_LINE_FROM_MARK 0x10u /* a straight line from mark `from_mark` (at 0) to the last row */
#define MG_CH_JUMPS_AT_EVENTS 0x20u /* may jump at the axis values of the node's MG_ROLE_EVENTS rows: never joined across */
#define MG_CH_RANGE_OF_ROWS 0x40u  /* as a figure's x: the rows' span; a mark far beyond is named at the edge */

/* A named value of a code channel ("1 contact_lost"). Frozen. */
typedef struct mg_code {
  double value;
  const char* name; /* scene-grammar name, shown in terminal, CSV, JSON, reports, Python */
  const char* doc;
} mg_code;

typedef struct mg_channel_decl {
  uint32_t struct_size;
  const char* name;
  mg_dim dim;
  const char* label;        /* "valve lift"; NULL: the name with '_' as ' ' */
  const char* display_unit; /* NULL: SI or the scene's units */
  int32_t angle_frame;      /* MG_FRAME(i): frame i of mg_node_desc::frames; 0 none. For d/dphi: the angle counted */
  int32_t derivative_order; /* MG_ROLE_DERIVATIVE_FAMILY: 0 the value, 1, 2, 3 ...; -1 none */
  uint32_t flags;           /* MG_CH_* */
  const mg_code* codes;
  size_t code_count;
  const char* from_mark; /* MG_CH_LINE_FROM_MARK: the mark's label */
} mg_channel_decl;

/* MG_ROLE_DRAWING_TO_SCALE: one plane curve. Frozen. */
typedef struct mg_xy_pair {
  const char* x; /* channel names */
  const char* y;
  const char* layer; /* DXF layer */
  const char* label; /* legend; NULL: the layer */
  int32_t stroke;    /* 0 outline, 1 construction (dotted), 2 a part shown at rest */
} mg_xy_pair;

/* Points another output of the same node puts on this figure. Frozen. */
typedef struct mg_point_marks {
  const char* port;                /* an output of the same node */
  size_t row;                      /* the row of that output's table */
  const char* const* x_channels;   /* `count` channels of that row giving x */
  const char* const* labels;       /* `count` labels */
  size_t count;
  int32_t y_from_axis;             /* 1: y is that row's axis value */
  const char* caption;             /* "{axis}" is replaced by the host with the formatted axis value */
} mg_point_marks;

typedef struct mg_presentation {
  uint32_t struct_size;
  int32_t role; /* MG_ROLE_* */
  const mg_channel_decl* axis; /* NULL: undeclared */
  const mg_channel_decl* channels; /* declared ones (strided, MG_ELEMENT); others are plain */
  size_t channel_count;
  const char* x_channel; /* MG_ROLE_CURVE_OVER_CHANNEL */
  const mg_xy_pair* pairs; /* MG_ROLE_DRAWING_TO_SCALE */
  size_t pair_count;
  const mg_point_marks* points;
  size_t point_count;
  const char* figure_title; /* the host adds " of " and the nodes */
  const char* caption;      /* said under the figure; NULL: nothing */
} mg_presentation;

/* An angle reference. Frames belong to a node type, which names them; the host compares only the
   index and shows the label and tag. */
typedef struct mg_angle_frame {
  uint32_t struct_size;
  const char* id;       /* scene-grammar name */
  const char* label;    /* "angle from the top of the lobe" */
  const char* unit_tag; /* shown as "deg (tag)" */
  const char* zero;     /* where zero is, in words (describe, JSON) */
  /* Optional mapping from another frame: this = scale * base + offset_param (SI). A figure is drawn
     in this frame when every node has offset_param set, else in the base frame. MG_FRAME(i), 0: none. */
  int32_t base_frame;
  double scale;
  const char* offset_param;
  /* Optional periodic marks every mark_spacing (0: none), labelled in turn; angles quoted as
     |a - nearest| + before/after + label. */
  double mark_spacing;
  const char* const* mark_labels;
  size_t mark_label_count;
  const char* before;
  const char* after;
} mg_angle_frame;

/* A note the node makes while computing `output` when parameter `when_param` is given (NULL:
   always): a host that prints notes wants that output. */
typedef struct mg_note_decl {
  uint32_t struct_size;
  const char* output;
  const char* when_param;
  const char* doc;
} mg_note_decl;

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_PRESENT_H */
