#pragma once
// The input columns of a sweep's rows as numbers, made column by column on worker threads: what
// a Python DataFrame of the rows holds, without a row's text or a Python object in between.
#include <mechgraph/host/sweep_rows.hpp>

#include <cstddef>
#include <vector>

namespace mechgraph::python {

/// Column v holds rows.input_number(case, v) of the n rows, row r being case `cases[r]` (case r
/// when `cases` is null): each value as the row shows it, read back. NaN where a row holds text or
/// nothing. Made in chunks on `threads` workers.
std::vector<std::vector<double>> input_number_columns(const host::SweepRows& rows, std::size_t n, const std::size_t* cases,
                                                      unsigned threads);

}  // namespace mechgraph::python
