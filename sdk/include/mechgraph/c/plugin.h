/* mechgraph SDK 1.x: the plugin and its one entry (docs/design/sdk-1.0.md, section 1.3).
 *
 * A plugin exports exactly one function, mechgraph_plugin_entry_1. Its name carries the SDK's
 * major version, so a plugin for another major is never mistaken for this one. The host checks
 * the returned mg_plugin: sdk_major equal to its own and sdk_minor not above its own (GStreamer's
 * rule); a refusal names both versions.
 */
#ifndef MECHGRAPH_C_PLUGIN_H
#define MECHGRAPH_C_PLUGIN_H

#include <mechgraph/c/base.h>
#include <mechgraph/c/host.h>

MG_EXTERN_C_BEGIN

struct mg_node_type;

typedef struct mg_plugin {
  uint32_t struct_size;
  uint16_t sdk_major, sdk_minor; /* what the plugin was compiled against: MG_SDK_MAJOR, MG_SDK_MINOR */
  const char* plugin_id;         /* "cams": the scene grammar's names */
  const char* plugin_version;    /* semantic version MAJOR.MINOR.PATCH */
  const char* sdk_version;       /* "1.0.3", informative */
  const char* built_with;        /* "clang 14.0.6", informative only: never compared */
  size_t node_type_count;
  const struct mg_node_type* const* node_types;
  size_t interface_count;        /* interfaces its objects implement, for `mechgraph plugins` */
  const char* const* interfaces; /* "mechgraph.cam_law/1" ... */
} mg_plugin;

/* Called once in the probe's child process and once in the host. NULL: the plugin refuses to
   load and says why through `why`. Everything reachable from the result is immutable and lives
   until the process ends. Must not throw. */
typedef const mg_plugin* mg_plugin_entry_fn(const mg_host* host, mg_text_sink why);
#define MG_PLUGIN_ENTRY "mechgraph_plugin_entry_1"

/* The declaration a plugin's definition matches. */
MG_PLUGIN_EXPORT const mg_plugin* mechgraph_plugin_entry_1(const mg_host* host, mg_text_sink why);

MG_EXTERN_C_END

#endif /* MECHGRAPH_C_PLUGIN_H */
