#include "input_columns.hpp"

#include <mechgraph/chunked_work.hpp>

#include <algorithm>
#include <string>

namespace mechgraph::python {

std::vector<std::vector<double>> input_number_columns(const host::SweepRows& rows, std::size_t n, const std::size_t* cases,
                                                      unsigned threads) {
  const std::size_t width = rows.input_headers().size();
  constexpr std::size_t rows_a_chunk = 1 << 16;
  const std::size_t chunks_a_column = (n + rows_a_chunk - 1) / rows_a_chunk;
  std::vector<std::vector<double>> columns(width, std::vector<double>(n));
  // `cell`: one scratch string a worker, so that a million rows make no string each.
  run_chunks(width * chunks_a_column, threads, [] { return std::string(); }, [&](std::string& cell, std::size_t chunk) {
    const std::size_t v = chunk / chunks_a_column, first = chunk % chunks_a_column * rows_a_chunk;
    for (std::size_t r = first; r < std::min(n, first + rows_a_chunk); ++r)
      columns[v][r] = rows.input_number(cases ? cases[r] : r, v, cell);
  });
  return columns;
}

}  // namespace mechgraph::python
