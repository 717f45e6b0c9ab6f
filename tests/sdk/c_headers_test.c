/* The SDK's C headers are C: every header compiles as C11 with -Wall -Wextra -pedantic -Werror, by
   gcc and by clang (ctest "sdk: the C headers compile as C11 ..."), and their macros work in C.
   Returns 0 when every check holds, else the number of the first that fails. */
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
#include <mechgraph/c/object.h>
#include <mechgraph/c/object_cxx.h>
#include <mechgraph/c/plugin.h>
#include <mechgraph/c/present.h>
#include <mechgraph/c/sdk_lib.h>
#include <mechgraph/c/value.h>

#include <string.h>

_Static_assert(MG_SDK_MAJOR == 1, "SDK 1.x headers");
_Static_assert(sizeof(mg_dim) == 8, "eight exponents, one byte each");
_Static_assert(sizeof(mg_status) == 4, "statuses are int32_t");

/* A text sink that appends into a fixed buffer. */
typedef struct buffer {
  char text[64];
  size_t size;
} buffer;
static void buffer_append(void* self, const char* text, size_t size) {
  buffer* b = (buffer*)self;
  if (size > sizeof b->text - 1 - b->size) size = sizeof b->text - 1 - b->size;
  memcpy(b->text + b->size, text, size);
  b->size += size;
  b->text[b->size] = '\0';
}

/* A struct as an older 1.x writer had it: without its last fields. */
static mg_port_decl older_port(void) {
  mg_port_decl p;
  memset(&p, 0, sizeof p);
  p.struct_size = (uint32_t)offsetof(mg_port_decl, display_unit);
  p.name = "out";
  p.kind = MG_VALUE_SCALAR;
  return p;
}

/* A writer whose structs are larger than the reader's (a newer 1.x): arrays are strided by it. */
typedef struct newer_counter {
  mg_counter_decl base;
  double added_later;
} newer_counter;

int main(void) {
  buffer b;
  mg_text_sink sink;
  mg_port_decl port = older_port();
  newer_counter counters[3];
  mg_value v;
  mg_str s;
  size_t i;
  b.size = 0;
  b.text[0] = '\0';
  sink.self = &b;
  sink.append = buffer_append;
  sink.append(sink.self, "base_", 5);
  sink.append(sink.self, "radius", 6);
  if (strcmp(b.text, "base_radius") != 0) return 1;
  if (!MG_HAS_FIELD(&port, mg_port_decl, flags)) return 2;
  if (MG_HAS_FIELD(&port, mg_port_decl, display_unit)) return 3;
  if (MG_HAS_FIELD(&port, mg_port_decl, presentation)) return 4;
  port.struct_size = sizeof port;
  if (!MG_HAS_FIELD(&port, mg_port_decl, presentation)) return 5;
  memset(counters, 0, sizeof counters);
  for (i = 0; i < 3; ++i) {
    counters[i].base.struct_size = sizeof counters[i];
    counters[i].base.name = i == 0 ? "a" : i == 1 ? "b" : "c";
  }
  if (strcmp(MG_ELEMENT(mg_counter_decl, &counters[0].base, 2)->name, "c") != 0) return 6;
  v.kind = MG_VALUE_SCALAR;
  v.reserved = 0;
  v.u.scalar = 2.5;
  if (v.u.scalar != 2.5) return 7;
  s.data = "x";
  s.size = 1;
  if (s.size != 1) return 8;
  if (strcmp(MG_PLUGIN_ENTRY, "mechgraph_plugin_entry_1") != 0) return 9;
  return 0;
}
