#pragma once
// Closed plane curves (a table with Table::closed_curve: channels x, y and any prefix_x, prefix_y)
// as a DXF drawing a CAD program opens: one closed polyline per curve, each on its own layer
// (CONTOUR for x/y, else the prefix in capitals, e.g. PITCH), coordinates in millimetres
// ($INSUNITS = 4). Written with dxflib (DXF R2000).
#include <mechgraph/value.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace mechgraph::cli {

/// Whether `t` holds a curve this writer can draw (closed_curve with length channels x and y).
bool is_drawable_curve(const Table& t);

/// Writes `t` to `file`, each of `notes` (the producing node's notes, e.g. which way a cam contour
/// turns) as a 999 comment line at the top; throws IoError when the file cannot be written.
void write_dxf(const std::filesystem::path& file, const Table& t, const std::vector<std::string>& notes = {});

}  // namespace mechgraph::cli
