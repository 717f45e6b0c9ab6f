#pragma once
// What the registry checks about a plugin file before any of its code runs, even in the probe's
// child process: who may have written it, that it is a whole ELF shared library for this machine,
// and that it exports the plugin entry. A file that fails here is never mapped by the dynamic
// loader, so its static constructors never run. Private to libmechgraph.
#include <filesystem>
#include <string>
#include <vector>

namespace mechgraph::detail {

/// Throws PluginError (naming `where`) unless only its owner, this user or root, can write the file
/// or folder.
void check_plugin_ownership(const std::filesystem::path& path, const std::string& where, bool folder);

/// Throws PluginError unless `file` is a whole 64-bit little-endian ELF shared library for this
/// processor: every header and loadable segment within the file (a truncated library would be
/// mapped past its end and take the process down with SIGBUS).
void check_plugin_elf(const std::filesystem::path& file, const std::string& where);

/// Which of `names` the file's dynamic symbol table (.dynsym) defines as a global or weak symbol
/// (result[i] for names[i]), read from the file with bounds on every offset and size, without
/// mapping it, in one pass over the table. A file without section headers or without .dynsym
/// defines nothing. Throws PluginError on a table that lies beyond the file. Call after
/// check_plugin_elf.
std::vector<bool> plugin_exports_symbols(const std::filesystem::path& file, const std::vector<std::string>& names,
                                         const std::string& where);

}  // namespace mechgraph::detail
