// Fuzz target: the sweep's --cases reader (read_cases_csv), fed through a memfd so it reads a
// regular file exactly as from disk (bounded read, BOM, quotes, units, words). It may refuse a
// file only with SceneError; what it accepts must have a header, at least one case, rows as wide
// as the header, finite numbers only, and its values' texts kept within the file's size.
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
    const std::size_t width = table.variables.size();
    if (width == 0 || table.size() == 0 || table.size() > mechgraph::max_sweep_cases || table.size() * width > mechgraph::max_case_cells)
      __builtin_trap();
    // Kept as numbers with each value's text beside them: one of each a value, the texts within
    // the file (a bare number's unit is not repeated), in order.
    const auto& written = table.numbers.written;
    const std::size_t values = table.size() * width;
    if (!table.cases.empty() || table.numbers.si.size() != values || written.ends.size() != values ||
        written.in_column_unit.size() != values || written.dimensions.size() != values || written.column_units.size() != width ||
        written.text.size() > size || written.ends.back() != written.text.size())
      __builtin_trap();
    for (std::size_t k = 1; k < values; ++k)
      if (written.ends[k] < written.ends[k - 1]) __builtin_trap();
    mechgraph::CaseValue scratch;
    for (std::size_t i = 0; i < table.size(); ++i) {
      for (std::size_t v = 0; v < width; ++v) {
        const mechgraph::CaseValue& value = table.cell(i, v, scratch);
        if (value.text.empty()) __builtin_trap();  // every cell holds something
        if (value.si && !std::isfinite(*value.si)) __builtin_trap();
        (void)table.shown(i, v);
      }
    }
  } catch (const mechgraph::SceneError& e) {
    if (std::string(e.what()).size() > 4000) __builtin_trap();  // messages quote user text only in excerpts
  }
  return 0;
}
