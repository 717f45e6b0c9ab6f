#include "plugin_probe.hpp"

#include "c_node_type.hpp"
#include "plugin_handshake.hpp"

#include <mechgraph/errors.hpp>

#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace mechgraph::detail {
namespace {

// What the child writes to its pipe just before it ends: one verdict byte, then for a refusal the
// reason (at most one atomic pipe write). Nothing written (the plugin ended the child itself) is a
// refusal like a crash.
constexpr char probe_accepted = 'k';
constexpr char probe_refused = 'r';
constexpr std::size_t probe_report_limit = 4000;  // below PIPE_BUF: one write, whole or not at all

[[noreturn]] void probe_child_main(const std::filesystem::path& file, const std::string& where, int report) {
  // The parent's crash handlers (a test framework's, a host's) must not report the child's crash.
  for (int sig : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT}) ::signal(sig, SIG_DFL);
  std::string verdict(1, probe_accepted);
  try {
    void* handle = ::dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* e = ::dlerror();
      throw_plugin_load_failure(where, e ? e : "unknown reason");
    }
    // An SDK 1.x plugin (the C boundary) first, then the pre-1.0 C++ one.
    if (void* c_entry = ::dlsym(handle, MG_PLUGIN_ENTRY)) {
      const mg_plugin& p = checked_c_plugin(reinterpret_cast<mg_plugin_entry_fn*>(c_entry), where);
      // Its C descriptions read whole, as a host that calls every type through C reads them; and
      // what a host of its C++ layer asks of each type to call it as itself (c/node_cxx.h).
      (void)checked_c_plugin_node_types(p, where, true);
      for (std::size_t i = 0; i < p.node_type_count; ++i) (void)same_cxx_node_type(*p.node_types[i]);
    } else {
      void* entry = ::dlsym(handle, plugin_entry_name);
      if (!entry)
        throw PluginError(where + ": has no entry '" + std::string(plugin_entry_name) +
                          "'; it is not a mechgraph plugin (a plugin declares one with MECHGRAPH_PLUGIN)");
      const PluginDescriptor& d = checked_plugin_descriptor(reinterpret_cast<PluginEntry*>(entry), where);
      (void)checked_plugin_node_types(d, where);
    }
  } catch (const std::exception& e) {
    verdict = std::string(1, probe_refused) + e.what();
  } catch (...) {
    verdict = std::string(1, probe_refused) + where + ": loading it threw something that is not a std::exception; refused";
  }
  if (verdict.size() > probe_report_limit) verdict.resize(probe_report_limit);
  (void)!::write(report, verdict.data(), verdict.size());
  ::_exit(0);
}

// fork() may fail for a moment (EAGAIN at a process limit): a few tries before the file is refused.
pid_t fork_with_retries() {
  pid_t child = -1;
  for (int attempt = 0; attempt < 4; ++attempt) {
    child = ::fork();
    if (child >= 0 || errno != EAGAIN) return child;
    ::usleep(20000u << attempt);
  }
  return child;
}

}  // namespace

void probe_plugin_in_child(const std::filesystem::path& file, const std::string& where, ProbeCache& cache) {
  const std::string key = probe_key(file);
  if (cache.accepted_before(key)) return;
  // Non-blocking: a process the plugin started may hold the write end open after the child ends.
  int report[2];
  if (::pipe2(report, O_CLOEXEC | O_NONBLOCK) != 0)
    throw PluginError(where + ": cannot be probed before loading (no pipe: " + std::strerror(errno) +
                      "); refused, since nothing is loaded unprobed");
  const pid_t child = fork_with_retries();
  if (child < 0) {
    const int error = errno;
    ::close(report[0]);
    ::close(report[1]);
    throw PluginError(where + ": cannot be probed before loading (no process: " + std::strerror(error) +
                      ", a process limit?); refused, since nothing is loaded unprobed");
  }
  if (child == 0) {
    ::close(report[0]);
    probe_child_main(file, where, report[1]);
  }
  ::close(report[1]);
  int status = 0;
  for (int waited_ms = 0;; waited_ms += 10) {
    const pid_t done = ::waitpid(child, &status, WNOHANG);
    if (done == child) break;
    if (done < 0) {  // someone else reaped it (a SIGCHLD handler set to SIG_IGN): no exit status
      status = 0;
      break;
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
  char buffer[probe_report_limit];
  ssize_t got = 0;
  do got = ::read(report[0], buffer, sizeof buffer);
  while (got < 0 && errno == EINTR);
  ::close(report[0]);
  if (WIFSIGNALED(status))
    throw PluginError(where + ": loading it crashed (signal " + std::to_string(WTERMSIG(status)) + ", " +
                      ::strsignal(WTERMSIG(status)) + ") in its static constructors, its entry or its node type "
                      "factory; refused");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || got < 1)
    throw PluginError(where + ": loading it ended the process" +
                      (WIFEXITED(status) ? " with exit code " + std::to_string(WEXITSTATUS(status)) : std::string()) +
                      " (in its static constructors, its entry or its node type factory); refused");
  if (buffer[0] == probe_refused) throw PluginError(std::string(buffer + 1, static_cast<std::size_t>(got - 1)));
  if (buffer[0] != probe_accepted || got != 1)
    throw PluginError(where + ": loading it gave the probe no verdict it understands; refused");
  cache.remember(key);
}

}  // namespace mechgraph::detail
