// Fuzz target: the row checker --resume and merge read rows back with (RowChecker, both formats).
// The first byte picks the format and the number of input columns, the rest is the file's lines.
// It may refuse only with UsageError; a row it accepts has a case number below the sweep's count,
// after the previous one.
#include <mechgraph/host/usage_error.hpp>
#include <mechgraph/host/sweep_rows.hpp>

#include <cstdint>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  using namespace mechgraph::host;
  const RowFormat format = data[0] & 1 ? RowFormat::jsonl : RowFormat::csv;
  const std::size_t inputs = (data[0] >> 1) & 3;
  const std::size_t shards = 1 + ((data[0] >> 3) & 3);
  const RowRules rules{format, 1000, 0, shards, data[0] & 0x80 ? std::optional<std::size_t>() : std::optional<std::size_t>(inputs), {}};
  RowChecker checker(rules, "fuzz.csv");
  std::istringstream lines(std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  std::string line;
  std::size_t previous = 0;
  bool any = false;
  try {
    for (std::size_t number = 1; std::getline(lines, line); ++number) {
      if (number == 1 && format == RowFormat::csv) {
        checker.header(line, number);
        continue;
      }
      const RowChecker::Row row = checker.row(line, number);
      if (row.index >= 1000 || row.index % shards != 0 || (any && row.index <= previous)) __builtin_trap();
      previous = row.index;
      any = true;
    }
  } catch (const UsageError&) {
  }
  return 0;
}
