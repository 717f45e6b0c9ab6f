#pragma once
// Closed plane curves (a table with Table::closed_curve whose port declares x/y pairs, role
// drawing_to_scale) as a DXF drawing a CAD program opens: one closed polyline per pair, each on its
// declared layer in capitals, coordinates in millimetres ($INSUNITS = 4). Written with dxflib (DXF R2000).
#include <mechgraph/presentation.hpp>
#include <mechgraph/value.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace mechgraph::cli {

/// Whether `t` holds a curve this writer can draw (closed_curve and a declared pair of length channels).
bool is_drawable_curve(const Table& t, const Presentation& presentation);

/// Writes `t` to `file`, each of `notes` (the producing node's notes, e.g. which way a part turns)
/// as a 999 comment line at the top; throws IoError when the file cannot be written.
void write_dxf(const std::filesystem::path& file, const Table& t, const Presentation& presentation,
               const std::vector<std::string>& notes = {});

}  // namespace mechgraph::cli
