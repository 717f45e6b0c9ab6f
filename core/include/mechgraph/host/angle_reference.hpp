#pragma once
// Which angle a value counts, as its port declares it (presentation.hpp: a port's or a channel's
// angle frame, whose unit_tag is shown after degrees: "deg (shaft)", "mm/deg (drum)"). One rule for
// the terminal, the report, the sweep's CSV header and Python (docs/design/sdk-1.0.md, 1.6).
#include <mechgraph/display_units.hpp>
#include <mechgraph/node.hpp>

#include <string>

namespace mechgraph::host {

/// The tag of the frame `frame_id` of `info` for a value of dimension `d`: the frame's unit_tag
/// ("shaft"), or "" when `d` has no angle in it or the type declares no such frame.
std::string angle_reference(const NodeInfo& info, const std::string& frame_id, const Dimension& d);

/// The tag of a scalar or series port's values (its own angle frame, its dimension).
inline std::string angle_reference(const NodeInfo& info, const PortSpec& port) {
  return angle_reference(info, port.angle_frame, port.dimension);
}

/// The tag of table column `name` of dimension `d` of `port`: the frame its channel (or axis)
/// declaration names; "" when it declares none.
std::string column_angle_reference(const NodeInfo& info, const PortSpec& port, const std::string& name, const Dimension& d);

/// A unit with its reference and back (mechgraph/display_units.hpp): the labels' rule.
using mechgraph::unit_with_reference;
using mechgraph::unit_without_reference;

}  // namespace mechgraph::host
