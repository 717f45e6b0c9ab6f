#pragma once
#include <mechgraph/node.hpp>

namespace mechgraph::fits {

/// fit.iso286: limit deviations from ISO 286 designations ("20 mm", "H11", "d11").
std::shared_ptr<const NodeType> make_iso286_fit_type();
/// fit.explicit: the source's form, nominal size with upper and lower deviations for each part.
std::shared_ptr<const NodeType> make_explicit_fit_type();

}  // namespace mechgraph::fits
