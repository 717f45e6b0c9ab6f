// Threads that cannot start: under a process limit (RLIMIT_NPROC, as a container's pid limit
// gives) or an address-space limit (RLIMIT_AS: every thread's stack must be mapped), every command
// that runs work on threads does it on fewer, with the same results, or ends with a clean error and
// its exit code; never std::terminate (SIGABRT). The limits are set by prlimit(1) on the command;
// RLIMIT_NPROC binds no root process, so as root the command runs as the user nobody. Nobody keeps
// the capabilities to read and search any file (ambient DAC capabilities, which RLIMIT_NPROC does
// not exempt), so the test also runs from a checkout in a folder only root may enter (mktemp -d).
#include "hostile/hostile_support.hpp"
#include "sanitizer_build.hpp"

#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

using namespace mechgraph::hostile;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

constexpr const char* prlimit = "/usr/bin/prlimit";
constexpr const char* setpriv = "/usr/bin/setpriv";

// The commands under test: each asks for several threads where it has work for them.
std::vector<std::vector<std::string>> threaded_commands() {
  return {
      // the evaluator's pool and the Monte Carlo sampler's
      {"run", source_file("scenes/backlash_chain.yaml"), "--threads", "4", "--set", "chain.threads=4", "--set",
       "chain.samples=20000", "--json"},
      // the sweep's workers
      {"sweep", source_file("scenes/valvetrain_cams.yaml"), "--vary", "rpm=3000rpm:7000rpm:6", "--threads", "4",
       "--outputs", "ta_kurz.time_area"},
      // the conformance kit's thread-safety check
      {"plugin-test", "cam.kurz", "--threads", "8"},
  };
}

// `args` for mechgraph, run as `user` (empty: as is) with `limits` (prlimit options).
Outcome run_limited(const std::vector<std::string>& limits, const std::vector<std::string>& args, bool as_nobody,
                    const fs::path& cwd) {
  std::vector<std::string> argv;
  std::string program = prlimit;
  if (as_nobody) {
    program = setpriv;
    argv = {"--reuid=65534",
            "--regid=65534",
            "--clear-groups",
            "--inh-caps=+dac_override,+dac_read_search",
            "--ambient-caps=+dac_override,+dac_read_search",
            prlimit};
  }
  argv.insert(argv.end(), limits.begin(), limits.end());
  argv.push_back("--");
  argv.push_back(MECHGRAPH_CLI);
  argv.insert(argv.end(), args.begin(), args.end());
  return run_argv(program, argv, cwd, {}, std::chrono::seconds(300));
}

bool killed_or_aborted(const Outcome& o) { return o.exit_code < 0 || o.exit_code == 134 || o.timed_out; }

// Lines of `text` without the ones that vary from run to run (timings in JSON, the sweep's log).
std::string stable(const std::string& text) {
  std::string out;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    if (line.find("seconds") == std::string::npos && line.find("\"ms\"") == std::string::npos) out += line + "\n";
    start = end + 1;
  }
  return out;
}

}  // namespace

TEST_CASE("under a process limit no thread can start: every threaded command does its work on one, same results",
          "[hostile][threads][cli]") {
  const bool root = ::geteuid() == 0;
  // The plugin probe forks; its verdicts are cached per user, so a first run without the limit fills
  // a cache the limited runs read (a probe that cannot fork refuses the file: nothing loads unprobed).
  Scratch scratch("nproc");
#if defined(MECHGRAPH_TEST_ADDRESS_SANITIZER)
  // LeakSanitizer needs a thread of its own at exit, which this limit forbids: no leak check here
  // (the rest of the sanitized suite has it).
  ::setenv("ASAN_OPTIONS", "detect_leaks=0:abort_on_error=1:allocator_may_return_null=1", 1);
#endif
  if (root) REQUIRE(::chown(scratch.dir.c_str(), 65534, 65534) == 0);
  ::setenv("XDG_CACHE_HOME", scratch.dir.c_str(), 1);
  for (const auto& args : threaded_commands()) {
    INFO(args[0]);
    const Outcome free = run_limited({}, args, root, scratch.dir);
    REQUIRE(free.exit_code == 0);
    const Outcome limited = run_limited({"--nproc=1"}, args, root, scratch.dir);
    INFO(limited.err);
    CHECK_FALSE(killed_or_aborted(limited));
    CHECK(limited.exit_code == 0);
    if (args[0] == "plugin-test") {
      CHECK_THAT(limited.out, Contains("1 threads (of 8 asked; the rest could not start)"));
    } else {
      CHECK(stable(limited.out) == stable(free.out));  // the same numbers on one thread
    }
  }
  ::unsetenv("XDG_CACHE_HOME");
}

TEST_CASE("under an address-space limit threads that cannot map a stack are not started, no abort",
          "[hostile][threads][cli]") {
  // A 1 GiB stack for every thread and 3 GiB of address space: a thread or two start, the rest fail.
#if defined(MECHGRAPH_TEST_ADDRESS_SANITIZER) || defined(MECHGRAPH_TEST_THREAD_SANITIZER)
  // A sanitizer maps terabytes of shadow memory when the program starts, which no address-space
  // limit admits: the uninstrumented suite (the README's test command) tests this limit.
  WARN("built with a sanitizer, which cannot start under an address-space limit: not tested in this build");
  return;
#endif
  Scratch scratch("as");
  for (const auto& args : threaded_commands()) {
    INFO(args[0]);
    const Outcome free = run_limited({}, args, false, scratch.dir);
    REQUIRE(free.exit_code == 0);
    const Outcome limited = run_limited({"--stack=1073741824", "--as=3221225472"}, args, false, scratch.dir);
    INFO(limited.err);
    CHECK_FALSE(killed_or_aborted(limited));
    // Either it ran (on the threads it got) with the same results, or it said it ran out of memory.
    if (limited.exit_code == 0) {
      if (args[0] != "plugin-test") CHECK(stable(limited.out) == stable(free.out));
    } else {
      CHECK((limited.exit_code == 3 || limited.exit_code == 2));
    }
  }
}

TEST_CASE("plugin-test --threads is range-checked", "[hostile][threads][cli]") {
  const Outcome o = run_mechgraph({"plugin-test", "cam.kurz", "--threads", "100000"});
  CHECK(o.exit_code == 2);
  CHECK_THAT(o.err, Contains("--threads must be from 0") && Contains("256"));
  CHECK(run_mechgraph({"plugin-test", "cam.kurz", "--threads", "-3"}).exit_code == 2);
}
