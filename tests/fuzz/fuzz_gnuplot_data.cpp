// The data gnuplot reads (hosts/cli/gnuplot_data.cpp) from arbitrary bytes: the first bytes as
// doubles (any bit pattern: NaN, infinities, denormals), the rest as tic labels split at NUL. The
// datablock must hold numbers only, every line finite, and end with its terminator; the xtics
// command must be one line whose labels are gnuplot_string constants. A violation aborts (a find).
#include "gnuplot_data.hpp"

#include <mechgraph/text_escape.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

namespace {

void require(bool ok) {
  if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace mechgraph;
  const std::size_t count = size > 0 ? std::min<std::size_t>(data[0], (size - 1) / (2 * sizeof(double))) : 0;
  std::vector<double> x(count), y(count);
  std::size_t at = 1;
  for (std::size_t i = 0; i < count; ++i, at += 2 * sizeof(double)) {
    std::memcpy(&x[i], data + at, sizeof(double));
    std::memcpy(&y[i], data + at + sizeof(double), sizeof(double));
  }
  std::ostringstream block;
  cli::write_gnuplot_datablock(block, "curve0", {&x, &y});
  const std::string b = block.str();
  require(b.rfind("$curve0 << EOD\n", 0) == 0);
  require(b.size() >= 4 && b.compare(b.size() - 4, 4, "EOD\n") == 0);
  const std::string body = b.substr(15, b.size() - 19);
  require(body.find_first_not_of("0123456789.eE+- \n") == std::string::npos);
  std::istringstream lines(body);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream numbers(line);
    double a = 0, c = 0;
    require(static_cast<bool>(numbers >> a >> c) && std::isfinite(a) && std::isfinite(c));
  }

  std::vector<std::string> labels;
  const std::string rest(reinterpret_cast<const char*>(data) + std::min(at, size), size - std::min(at, size));
  for (std::size_t from = 0; from <= rest.size() && labels.size() < 32;) {
    const std::size_t end = std::min(rest.find('\0', from), rest.size());
    labels.push_back(rest.substr(from, end - from));
    from = end + 1;
  }
  std::ostringstream tics;
  cli::write_gnuplot_xtic_labels(tics, "rotate by -30", labels);
  const std::string t = tics.str();
  require(!first_invalid_utf8(t));
  require(t.find('\n') == t.size() - 1);  // one command
  std::string expected = "set xtics rotate by -30 (";
  for (std::size_t i = 0; i < labels.size(); ++i) expected += (i ? ", " : "") + gnuplot_string(labels[i]) + " " + std::to_string(i);
  require(t == expected + ")\n");
  return 0;
}
