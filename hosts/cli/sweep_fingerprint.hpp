#pragma once
// Which sweep a file of rows belongs to (sweep_file.hpp's manifest): a hash of the scene's text,
// the contents of every file it reads, the --set values, every case, the columns and the row
// format. `mechgraph sweep` writes it, --resume and merge compare it, and `mechgraph study --rows`
// checks that the rows it analyses are those of the study it is asked for.
#include <mechgraph/graph.hpp>
#include <mechgraph/host/sweep_rows.hpp>
#include <mechgraph/sweep/case_table.hpp>

#include <string>
#include <vector>

namespace mechgraph::cli {

/// The fingerprint, 16 hex digits.
std::string sweep_fingerprint(const std::string& scene_file, const std::vector<std::string>& sets, const CaseTable& table,
                              const Graph& graph, host::RowFormat format);

}  // namespace mechgraph::cli
