#pragma once
// The probe (GStreamer's plugin scanner is the model): a plugin file is loaded first in a child
// process, which runs its static constructors, its entry, the whole handshake and every node type's
// info(). Only a file the child accepted is loaded in this process; a crash, an abort, a hang or a
// refusal in the child refuses the file with the child's reason. Files accepted before are
// remembered by path, size, change time and inode (plugin_probe_cache.hpp). Private to libmechgraph.
#include "plugin_probe_cache.hpp"

#include <filesystem>
#include <string>

namespace mechgraph::detail {

/// Returns when the child loaded the file and accepted its handshake (or `cache` has it accepted
/// before, unchanged); otherwise throws PluginError naming `where` and the reason. A probe that
/// cannot run (no process or pipe to be had) refuses the file: nothing is loaded unprobed.
void probe_plugin_in_child(const std::filesystem::path& file, const std::string& where, ProbeCache& cache);

}  // namespace mechgraph::detail
