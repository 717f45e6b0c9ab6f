#pragma once
// What cam.table costs, said from its parameters before anything runs (CamLawDefinition::cost,
// NodeType::forecast). The rows: the numbers of `angles`, or the lines of `file` (counted, the file
// read with the same bound as the table itself; the count of a file is kept by path, size and time
// of change, so a sweep does not count it for every case). Per row:
//   - reading and checking it, and the quintic interpolant (twice: the law and its noise);
//   - smoothing: resolution or gcv, each least-squares solve is O(rows) (smoothing_spline.hpp), and
//     a search makes at most QuinticSmoother::most_solves of them;
//   - the searches over the law: a quintic piece per row (the size the nodes downstream see), and
//     a certified search halves a piece that rounding makes rough up to 4 times
//     (mechgraph/numerics/piecewise.hpp), so this node's summary counts 16 pieces a row. That is
//     the worst case; a smooth table costs far less (the calibration test,
//     tests/core/work_estimate_calibration_test.cpp, states by how much). The nodes downstream
//     count a piece a row at the host's ordinary cost: on a rough table they may cost more, but
//     never more than this node's own summary, which the budget has already admitted.
#include "cam_node.hpp"

#include <mechgraph/params.hpp>

namespace mechgraph::cams {

/// Pieces a search may resolve per row of the table (4 halvings), at worst.
inline constexpr double table_pieces_per_row = 16.0;

/// The rows `params` give (lists or file), an upper bound; 0 when the file cannot be read (the
/// evaluation says why).
double table_rows(const ParamSet& params);

CamLawCost table_cost(const ParamSet& params);

}  // namespace mechgraph::cams
