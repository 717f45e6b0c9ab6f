// Fuzz target: the sweep's --cases reader (read_cases_csv), fed through a memfd so it reads a
// regular file exactly as from disk (bounded read, BOM, quotes, units, words). It may refuse a
// file only with SceneError; what it accepts must have a header, at least one case, rows as wide
// as the header, and finite numbers only.
#include <mechgraph/errors.hpp>
#include <mechgraph/sweep/case_table.hpp>

#include <sys/mman.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const int fd = ::memfd_create("fuzz_cases", 0);
  if (fd < 0) __builtin_trap();
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, data, size, 0) != static_cast<ssize_t>(size)) __builtin_trap();
  const std::string path = "/proc/self/fd/" + std::to_string(fd);
  try {
    const mechgraph::CaseTable table = mechgraph::read_cases_csv(path);
    if (table.variables.empty() || table.cases.empty() || table.cases.size() > mechgraph::max_sweep_cases ||
        table.cases.size() * table.variables.size() > mechgraph::max_case_cells)
      __builtin_trap();
    for (std::size_t i = 0; i < table.cases.size(); ++i) {
      if (table.cases[i].size() != table.variables.size()) __builtin_trap();
      for (std::size_t v = 0; v < table.variables.size(); ++v) {
        const auto& value = table.cases[i][v];
        if (value.si && !std::isfinite(*value.si)) __builtin_trap();
        (void)table.shown(i, v);
      }
    }
  } catch (const mechgraph::SceneError& e) {
    if (std::string(e.what()).size() > 4000) __builtin_trap();  // messages quote user text only in excerpts
  }
  return 0;
}
