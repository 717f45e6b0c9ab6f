/* mechgraph SDK 1.x: domain objects passed between nodes (docs/design/sdk-1.0.md, section 1.7).
 *
 * An object is an opaque handle whose first member points at its vtable. It implements interfaces
 * (C function tables) that a consumer queries by name and version; a NULL answer means it does
 * not implement that one. Interface names starting "mechgraph." belong to the SDK
 * (the headers of mechgraph/c/domain); a plugin's private ones start with its id. Reference counts are
 * atomic; the last release destroys the object on its creator's side.
 */
#ifndef MECHGRAPH_C_OBJECT_H
#define MECHGRAPH_C_OBJECT_H

#include <mechgraph/c/base.h>

MG_EXTERN_C_BEGIN

typedef struct mg_object mg_object;

typedef struct mg_object_vtbl {
  uint32_t struct_size;
  void (*retain)(const mg_object* self);  /* atomic; any thread */
  void (*release)(const mg_object* self); /* the last one destroys, on the creator's side */
  /* The table of interface `name` at `version`, or NULL. The same pointer for the same question;
     tables live until the process ends. Every object answers its primary interface. */
  const void* (*query)(const mg_object* self, const char* name, uint32_t version);
  /* The node type that made it ("plugin.kind"), for messages: NUL-terminated, valid while the
     object lives. */
  const char* (*maker)(const mg_object* self);
  const void* origin;                          /* identity of the producing plugin's SDK layer */
} mg_object_vtbl;

/* Implementations put their data after it. */
struct mg_object {
  const mg_object_vtbl* vtbl;
};

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_OBJECT_H */
