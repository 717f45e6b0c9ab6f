#include <mechgraph/plugin_registry.hpp>
#include <mechgraph/scene.hpp>

#include <mechgraph/bounded_read.hpp>
#include <mechgraph/plugin_abi.hpp>
#include <mechgraph/semantic_version.hpp>

#include <boost/dll/runtime_symbol_info.hpp>
#include <boost/dll/shared_library.hpp>
#include <spdlog/spdlog.h>

#include <dlfcn.h>
#include <elf.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace mechgraph {
namespace {

using Library = boost::dll::shared_library;

// Libraries are kept for the whole process: plugins are never unloaded (docs/writing-plugins.md).
// The list is leaked on purpose so no static destructor can unload a library before objects it
// created are gone.
std::vector<std::shared_ptr<Library>>& all_libraries() {
  static auto* libraries = new std::vector<std::shared_ptr<Library>>();
  return *libraries;
}

template <class T>
std::shared_ptr<const T> tie_to_library(std::shared_ptr<const T> object, std::shared_ptr<const void> library) {
  // Members are destroyed in reverse order: the object first, then the library handle.
  struct Holder {
    std::shared_ptr<const void> library;
    std::shared_ptr<const T> object;
  };
  auto holder = std::make_shared<Holder>(Holder{std::move(library), object});
  return std::shared_ptr<const T>(holder, object.get());
}

// "abi4;gcc-12;cxx202002;glibcxx-abi1" -> {"abi": "4", "compiler": "gcc-12", "cxx": "202002", ...}
std::map<std::string, std::string> fingerprint_fields(const std::string& fingerprint) {
  std::map<std::string, std::string> out;
  std::stringstream ss(fingerprint);
  for (std::string item; std::getline(ss, item, ';');) {
    if (item.rfind("abi", 0) == 0) out["abi"] = item.substr(3);
    else if (item.rfind("cxx", 0) == 0) out["cxx"] = item.substr(3);
    else if (item.rfind("glibcxx-abi", 0) == 0) out["glibcxx-abi"] = item.substr(11);
    else out["compiler"] = item;
  }
  return out;
}

std::string cxx_standard_name(const std::string& cplusplus) {
  static const std::map<std::string, std::string> names{{"201402", "C++14"}, {"201703", "C++17"}, {"202002", "C++20"},
                                                        {"202100", "C++23"}, {"202302", "C++23"}};
  const auto it = names.find(cplusplus.substr(0, 6));
  return it == names.end() ? "__cplusplus " + cplusplus : it->second + " (__cplusplus " + cplusplus + ")";
}

// Names each field of the build fingerprint that differs and what to rebuild with.
std::string explain_fingerprint_mismatch(const std::string& plugin, const std::string& host) {
  const auto p = fingerprint_fields(plugin);
  const auto h = fingerprint_fields(host);
  auto field = [](const std::map<std::string, std::string>& m, const char* key) {
    const auto it = m.find(key);
    return it == m.end() ? std::string("unknown") : it->second;
  };
  std::vector<std::string> differences;
  if (field(p, "compiler") != field(h, "compiler"))
    differences.push_back("compiler: plugin " + field(p, "compiler") + ", mechgraph " + field(h, "compiler") +
                          " (build the plugin with the compiler that built mechgraph: CMAKE_CXX_COMPILER)");
  if (field(p, "cxx") != field(h, "cxx"))
    differences.push_back("C++ standard: plugin " + cxx_standard_name(field(p, "cxx")) + ", mechgraph " +
                          cxx_standard_name(field(h, "cxx")) + " (rebuild the plugin with " +
                          (h.count("cxx") && h.at("cxx").substr(0, 6) == "202002" ? "-std=c++20" : "mechgraph's standard") +
                          "; mechgraph_add_plugin() sets it unless a -std= compile option overrides it)");
  if (field(p, "glibcxx-abi") != field(h, "glibcxx-abi"))
    differences.push_back("libstdc++ string ABI: plugin _GLIBCXX_USE_CXX11_ABI=" + field(p, "glibcxx-abi") +
                          ", mechgraph " + field(h, "glibcxx-abi") + " (do not set _GLIBCXX_USE_CXX11_ABI)");
  if (field(p, "abi") != field(h, "abi"))
    differences.push_back("plugin ABI: plugin " + field(p, "abi") + ", mechgraph " + field(h, "abi"));
  std::string out = "was built with a toolchain this mechgraph cannot share C++ objects with (plugin '" + plugin +
                    "', mechgraph '" + host + "'); what differs:";
  for (const std::string& d : differences) out += "\n    " + d;
  if (differences.empty()) out += " the fingerprints' text; rebuild the plugin with the same toolchain";
  return out;
}

// Who may have written the file: only its owner, who must be this user or root.
void check_ownership(const std::filesystem::path& path, const std::string& where, bool folder) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw PluginError(where + ": cannot be read (" + std::strerror(errno) + ")");
  if (st.st_mode & (S_IWGRP | S_IWOTH))
    throw PluginError(where + ": the " + (folder ? "folder" : "file") +
                      " is writable by group or others, so anyone could plant code in it; refused "
                      "(chmod go-w '" + path.string() + "')");
  if (st.st_uid != ::geteuid() && st.st_uid != 0)
    throw PluginError(where + ": owned by user id " + std::to_string(st.st_uid) + ", neither you nor root; refused");
}

// An ELF sanity check before the dynamic loader maps the file: a truncated library would be
// mapped past its end and take the process down with SIGBUS.
void check_elf(const std::filesystem::path& file, const std::string& where) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw PluginError(where + ": cannot be opened");
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(in.tellg());
  in.seekg(0);
  Elf64_Ehdr h{};
  if (size < sizeof h || !in.read(reinterpret_cast<char*>(&h), sizeof h) || std::memcmp(h.e_ident, ELFMAG, SELFMAG) != 0)
    throw PluginError(where + ": not an ELF shared library (" + std::to_string(size) + " bytes)");
  if (h.e_ident[EI_CLASS] != ELFCLASS64 || h.e_ident[EI_DATA] != ELFDATA2LSB)
    throw PluginError(where + ": an ELF file for another word size or byte order than this machine's");
#if defined(__x86_64__)
  constexpr unsigned machine = EM_X86_64;
#elif defined(__aarch64__)
  constexpr unsigned machine = EM_AARCH64;
#else
  const unsigned machine = h.e_machine;
#endif
  if (h.e_machine != machine)
    throw PluginError(where + ": built for another processor (ELF machine " + std::to_string(h.e_machine) + ")");
  if (h.e_type != ET_DYN) throw PluginError(where + ": an ELF file but not a shared library");
  auto beyond = [&](std::uint64_t offset, std::uint64_t length) { return offset > size || length > size - offset; };
  if (beyond(h.e_phoff, std::uint64_t{h.e_phnum} * h.e_phentsize) ||
      (h.e_shoff != 0 && beyond(h.e_shoff, std::uint64_t{h.e_shnum} * h.e_shentsize)))
    throw PluginError(where + ": truncated (" + std::to_string(size) + " bytes; its headers reach further)");
  for (unsigned i = 0; i < h.e_phnum; ++i) {
    Elf64_Phdr ph{};
    in.seekg(static_cast<std::streamoff>(h.e_phoff + std::uint64_t{i} * h.e_phentsize));
    if (!in.read(reinterpret_cast<char*>(&ph), sizeof ph)) throw PluginError(where + ": truncated program headers");
    if (ph.p_type == PT_LOAD && beyond(ph.p_offset, ph.p_filesz))
      throw PluginError(where + ": truncated (" + std::to_string(size) + " bytes; a segment reaches byte " +
                        std::to_string(ph.p_offset + ph.p_filesz) + ")");
  }
}

// Loads the file in a child process before this one maps it (GStreamer's plugin scanner is the
// model): the child dlopens it, which runs its static constructors, and calls its entry. A library
// that crashes, aborts or hangs there takes only the child down; the parent reads how it ended and
// refuses the file with the reason. Anything else (a missing entry, a version mismatch) is left to
// the real load, which explains it better.
// Files that loaded cleanly in a child before, by path, size, change time and inode, so that a
// process start does not fork once per plugin every time: $XDG_CACHE_HOME/mechgraph/plugin-probes
// (else ~/.cache/...), one line per file, appended. A file that changes is probed again.
std::filesystem::path probe_cache_file() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "mechgraph" / "plugin-probes";
  if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "mechgraph" / "plugin-probes";
  return {};
}

std::string probe_key(const std::filesystem::path& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) return {};
  return file.string() + " " + std::to_string(st.st_size) + " " + std::to_string(st.st_ctim.tv_sec) + "." +
         std::to_string(st.st_ctim.tv_nsec) + " " + std::to_string(st.st_ino);
}

// The cache is only a shortcut: whatever is wrong with it (a FIFO or a folder in its place, a
// huge or garbled file) costs a probe, never a hang or a crash. Read with a bound, like any file
// this process does not control.
constexpr std::size_t probe_cache_limit = std::size_t{1} << 20;

bool probed_before(const std::string& key) {
  const std::filesystem::path cache = probe_cache_file();
  if (key.empty() || cache.empty()) return false;
  std::string text;
  try {
    text = read_bounded_file(cache, probe_cache_limit);
  } catch (const FileReadError& e) {
    spdlog::debug("plugin probe cache ignored: {}", e.what());
    return false;
  }
  std::string_view rest(text);
  while (!rest.empty()) {
    const std::size_t end = std::min(rest.find('\n'), rest.size());
    if (rest.substr(0, end) == key) return true;
    rest.remove_prefix(std::min(end + 1, rest.size()));
  }
  return false;
}

void remember_probe(const std::string& key) {
  const std::filesystem::path cache = probe_cache_file();
  if (key.empty() || cache.empty() || key.find('\n') != std::string::npos) return;
  std::error_code ec;
  std::filesystem::create_directories(cache.parent_path(), ec);
  // Only a regular file (or none) is appended to: a FIFO there would block the open, a device or
  // a folder is not ours to write. Too big: start again.
  struct stat st {};
  if (::lstat(cache.c_str(), &st) == 0) {
    if (!S_ISREG(st.st_mode)) return;
    if (static_cast<std::uintmax_t>(st.st_size) > probe_cache_limit / 2) std::filesystem::remove(cache, ec);
  }
  const int fd = ::open(cache.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC | O_NOCTTY, 0644);
  if (fd < 0) return;
  struct stat opened {};
  const std::string line = key + "\n";
  // One short append: whole lines even with several writers.
  if (::fstat(fd, &opened) == 0 && S_ISREG(opened.st_mode)) (void)!::write(fd, line.data(), line.size());
  ::close(fd);
}

// What the probe child reports through its pipe just before it ends. Nothing written (the plugin
// ended the child itself) is a refusal like a crash.
constexpr char probe_loaded = 'k';        // loaded, entry and node type factory ran: may be cached
constexpr char probe_not_plugin = 'n';    // no library, no entry, another ABI: the real load explains
constexpr char probe_threw = 'x';         // the entry or the factory threw: the real load explains

// In the child: load, call the entry and, when the handshake matches, the node type factory and
// every type's info(), so a crash in any of them takes only the child down.
[[noreturn]] void probe_child_main(const std::filesystem::path& file, int report) {
  // The parent's crash handlers (a test framework's, a host's) must not report the child's crash.
  for (int sig : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT}) ::signal(sig, SIG_DFL);
  char outcome = probe_not_plugin;
  if (void* handle = ::dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL)) {
    if (void* entry = ::dlsym(handle, plugin_entry_name)) {
      try {
        const PluginDescriptor* d = reinterpret_cast<PluginEntry*>(entry)();
        // Only a plugin of this ABI and toolchain shares our NodeTypeList layout.
        if (d && d->abi_version == plugin_abi_version && d->build_fingerprint &&
            std::string(d->build_fingerprint) == build_fingerprint && d->make_node_types) {
          const NodeTypeList types = d->make_node_types();
          for (const auto& t : types)
            if (t) (void)t->info();
          outcome = probe_loaded;
        }
      } catch (...) {
        outcome = probe_threw;
      }
    }
  }
  (void)!::write(report, &outcome, 1);
  ::_exit(0);
}

// Returns normally when the file may be loaded in this process (cached as good only when the
// child loaded it completely); throws PluginError when loading it crashed, hung or ended the child.
void probe_in_child(const std::filesystem::path& file, const std::string& where) {
  const std::string key = probe_key(file);
  if (probed_before(key)) return;
  // Non-blocking: a process the plugin started may hold the write end open after the child ends.
  int report[2];
  if (::pipe2(report, O_CLOEXEC | O_NONBLOCK) != 0) {
    spdlog::warn("{}: no pipe for the crash probe ({}); loaded without it", where, std::strerror(errno));
    return;
  }
  const pid_t child = ::fork();
  if (child < 0) {
    spdlog::warn("{}: no process for the crash probe ({}); loaded without it", where, std::strerror(errno));
    ::close(report[0]);
    ::close(report[1]);
    return;
  }
  if (child == 0) {
    ::close(report[0]);
    probe_child_main(file, report[1]);
  }
  ::close(report[1]);
  int status = 0;
  for (int waited_ms = 0;; waited_ms += 10) {
    const pid_t done = ::waitpid(child, &status, WNOHANG);
    if (done == child) break;
    if (done < 0) {  // someone else reaped it (a SIGCHLD handler set to SIG_IGN): no verdict
      spdlog::warn("{}: the crash probe's process could not be waited for ({}); loaded without its verdict", where,
                   std::strerror(errno));
      ::close(report[0]);
      return;
    }
    if (waited_ms >= 30000) {
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      ::close(report[0]);
      throw PluginError(where + ": loading it did not finish within 30 s (a hang in its static constructors, its "
                                "entry or its node type factory); refused");
    }
    ::usleep(10000);
  }
  char outcome = 0;
  ssize_t got = 0;
  do got = ::read(report[0], &outcome, 1);
  while (got < 0 && errno == EINTR);
  ::close(report[0]);
  if (WIFSIGNALED(status))
    throw PluginError(where + ": loading it crashed (signal " + std::to_string(WTERMSIG(status)) + ", " +
                      ::strsignal(WTERMSIG(status)) + ") in its static constructors, its entry or its node type "
                      "factory; refused");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || got != 1)
    throw PluginError(where + ": loading it ended the process" +
                      (WIFEXITED(status) ? " with exit code " + std::to_string(WEXITSTATUS(status)) : std::string()) +
                      " (in its static constructors, its entry or its node type factory); refused");
  // Only a file that loaded completely is remembered; anything else is probed again next time.
  if (outcome == probe_loaded) remember_probe(key);
}

// Calls into a plugin (its entry, its node type factory, a type's info()) and turns whatever it
// throws into a PluginError naming the plugin: a throw of a non-std type must not end the host.
template <class F>
auto call_plugin(const std::string& where, const char* what, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const PluginError&) {
    throw;
  } catch (const std::exception& e) {
    throw PluginError(where + ": " + what + " threw an exception (" + quoted_text_excerpt(e.what(), 200) + "); refused");
  } catch (...) {
    throw PluginError(where + ": " + what + " threw something that is not a std::exception (a defect of the plugin); refused");
  }
}

}  // namespace

std::shared_ptr<const DomainObject> RegisteredType::keep_alive(std::shared_ptr<const DomainObject> object) const {
  if (!object || !library) return object;
  return tie_to_library(std::move(object), library);
}

void PluginRegistry::load_file(const std::filesystem::path& given) {
  // One absolute, canonical name for the probe, its cache and the loader: dlopen("crash.so")
  // without a slash searches the library path, not the folder the name was given in, so a
  // relative name would probe one file (or none) and load another.
  std::error_code ec_path;
  const std::filesystem::path file = std::filesystem::canonical(given, ec_path);
  if (ec_path || !std::filesystem::is_regular_file(file, ec_path))
    throw PluginError("plugin '" + given.string() + "': no such file");
  const std::string where = "plugin '" + file.string() + "'";
  check_ownership(file, where, false);
  check_elf(file, where);
  probe_in_child(file, where);
  auto library = std::make_shared<Library>();
  boost::dll::fs::error_code ec;
  library->load(boost::dll::fs::path(file.string()), boost::dll::load_mode::rtld_now | boost::dll::load_mode::rtld_local, ec);
  if (ec || !library->is_loaded()) {
    // The dynamic loader's own words say what is missing (a library, a symbol).
    std::string reason = ec.message();
    if (void* h = ::dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL)) ::dlclose(h);
    else if (const char* e = ::dlerror()) reason = e;
    if (reason.find("libmechgraph.so") != std::string::npos)
      throw PluginError(where + ": cannot be loaded (" + reason + "): it was built against another mechgraph SDK; rebuild it "
                        "against this mechgraph " MECHGRAPH_SDK_VERSION " (find_package(mechgraph CONFIG) of this install)");
    throw PluginError(where + ": cannot be loaded as a shared library (" + reason + ")");
  }
  if (!library->has(plugin_entry_name)) {
    if (library->has(legacy_plugin_entry_name))
      throw PluginError(where + ": was built for mechgraph plugin ABI 3 or older (its entry is the old '" +
                        std::string(legacy_plugin_entry_name) + "' alias); this mechgraph " MECHGRAPH_SDK_VERSION
                        " uses ABI version " + std::to_string(plugin_abi_version) +
                        "; rebuild the plugin against this mechgraph's SDK (find_package(mechgraph " MECHGRAPH_SDK_VERSION
                        " CONFIG) and mechgraph_add_plugin)");
    throw PluginError(where + ": has no entry '" + std::string(plugin_entry_name) +
                      "'; it is not a mechgraph plugin (a plugin declares one with MECHGRAPH_PLUGIN)");
  }
  // From here on the plugin's code runs in this process: it stays mapped even when it is refused
  // (an object it threw, a static it registered, may still point into it).
  if (lifetime_ == Lifetime::process) all_libraries().push_back(library);
  auto* entry = library->get<PluginEntry>(plugin_entry_name);
  const PluginDescriptor* d = call_plugin(where, "its entry", [&] { return entry(); });
  if (!d) throw PluginError(where + ": its entry returned no descriptor");
  if (d->abi_version != plugin_abi_version)
    throw PluginError(where + " was built for plugin ABI version " + std::to_string(d->abi_version) +
                      ", this mechgraph " MECHGRAPH_SDK_VERSION " uses ABI version " + std::to_string(plugin_abi_version) +
                      "; rebuild the plugin against this mechgraph's SDK (find_package(mechgraph " MECHGRAPH_SDK_VERSION
                      " CONFIG) and mechgraph_add_plugin)");
  const std::string id = d->plugin_id ? d->plugin_id : "";
  if (!d->build_fingerprint || std::string(d->build_fingerprint) != build_fingerprint)
    throw PluginError(where + " ('" + id + "') " +
                      explain_fingerprint_mismatch(d->build_fingerprint ? d->build_fingerprint : "", build_fingerprint));
  if (id.empty()) throw PluginError(where + ": its descriptor has an empty plugin id");
  for (const PluginInfo& p : plugins_)
    if (p.id == id) throw PluginError(where + ": plugin id '" + id + "' is already loaded from '" + p.path.string() + "'");
  if (!d->make_node_types) throw PluginError(where + ": its descriptor has no node type factory");
  const std::string version = d->plugin_version ? d->plugin_version : "";
  if (!SemanticVersion::parse(version))
    throw PluginError(where + " ('" + id + "'): its version '" + version +
                      "' is not a semantic version MAJOR.MINOR.PATCH (e.g. \"0.1.0\"); fix the MECHGRAPH_PLUGIN line");

  NodeTypeList types = call_plugin(where + " ('" + id + "')", "its node type factory", [&] { return d->make_node_types(); });
  std::shared_ptr<const void> keep = library;
  std::set<std::string> own;
  PluginInfo info{id, version, d->build_fingerprint, file, {}, d->sdk_version ? d->sdk_version : ""};
  std::vector<std::pair<std::string, RegisteredType>> added;
  for (auto& t : types) {
    if (!t) throw PluginError(where + ": returned an empty node type");
    const std::string name = call_plugin(where + " ('" + id + "')", "a node type's info()", [&] { return t->info().type; });
    if (name.empty()) throw PluginError(where + ": a node type has an empty name");
    if (const RegisteredType* other = find(name)) {
      std::string other_path;
      for (const PluginInfo& p : plugins_)
        if (p.id == other->plugin_id) other_path = p.path.string();
      throw PluginError(where + " ('" + id + "') provides node type '" + name + "', which plugin '" +
                        other->plugin_id + "' (" + other_path + ") already provides");
    }
    if (!own.insert(name).second) throw PluginError(where + " provides node type '" + name + "' twice");
    // Port, parameter and effect names become CSV headers, file names and plot titles: they follow
    // the grammar of scene names (a port called "../x" or "a,b" is a defect of the plugin).
    const NodeInfo& described = call_plugin(where + " ('" + id + "')", "a node type's info()", [&]() -> const NodeInfo& { return t->info(); });
    const auto check_name = [&](const std::string& what, const std::string& n) {
      if (const std::string why = name_problem(n); !why.empty())
        throw PluginError(where + " ('" + id + "'): node type '" + name + "' has a " + what + " whose name " + why);
    };
    for (const PortSpec& port : described.inputs) check_name("input port", port.name);
    for (const PortSpec& port : described.outputs) check_name("output port", port.name);
    for (const EffectSpec& effect : described.effects) check_name("effect", effect.name);
    for (const ParamSpec& param : described.params) {
      check_name("parameter", param.name);
      for (const ParamSpec& field : param.fields) check_name("record field", field.name);
    }
    info.node_types.push_back(name);
    added.emplace_back(name, RegisteredType{tie_to_library(t, keep), keep, id});
  }
  for (auto& a : added) types_.push_back(std::move(a));
  spdlog::debug("loaded plugin '{}' {} from {} ({} node types)", id, info.version, file.string(), info.node_types.size());
  plugins_.push_back(std::move(info));
}

void PluginRegistry::load_directory(const std::filesystem::path& folder) {
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) throw PluginError("plugin folder '" + folder.string() + "' does not exist");
  check_ownership(folder, "plugin folder '" + folder.string() + "'", true);
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.is_regular_file() && entry.path().extension() == ".so") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    try {
      load_file(f);
    } catch (const PluginError& e) {
      spdlog::warn("skipped: {}", e.what());
      skipped_.push_back({f, e.what()});
    }
  }
}

std::filesystem::path PluginRegistry::builtin_plugin_dir() {
  boost::dll::fs::error_code ec;
  const auto library = boost::dll::this_line_location(ec);  // this very libmechgraph.so
  if (ec) return {};
  return (std::filesystem::path(library.string()).parent_path() / "mechgraph" / "plugins").lexically_normal();
}

std::vector<std::filesystem::path> PluginRegistry::search_path(const std::vector<std::filesystem::path>& extra, bool only) {
  std::vector<std::filesystem::path> candidates(extra.begin(), extra.end());
  if (!only) {
    if (const char* env = std::getenv("MECHGRAPH_PLUGIN_PATH"); env && *env) {
      std::stringstream ss(env);
      for (std::string item; std::getline(ss, item, ':');)
        if (!item.empty()) candidates.emplace_back(item);
    }
    if (auto builtin = builtin_plugin_dir(); !builtin.empty()) candidates.push_back(builtin);
  }
  std::vector<std::filesystem::path> out;
  std::set<std::filesystem::path> seen;
  for (const auto& folder : candidates) {
    std::error_code ec;
    auto key = std::filesystem::weakly_canonical(folder, ec);
    if (ec) key = folder.lexically_normal();
    if (seen.insert(key).second) out.push_back(folder);
  }
  return out;
}

const RegisteredType* PluginRegistry::find(std::string_view type) const {
  for (const auto& [name, t] : types_)
    if (name == type) return &t;
  return nullptr;
}

std::vector<std::string> PluginRegistry::type_names() const {
  std::vector<std::string> out;
  for (const auto& [name, t] : types_) out.push_back(name);
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::string> PluginRegistry::effect_names() const {
  std::set<std::string> names;
  for (const auto& [name, t] : types_)
    for (const EffectSpec& e : t.type->info().effects) names.insert(e.name);
  return {names.begin(), names.end()};
}

}  // namespace mechgraph
