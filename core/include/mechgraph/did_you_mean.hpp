#pragma once
// Messages for unknown names: the closest valid name and the list of valid ones, e.g.
// "unknown node type 'shape.circel'; did you mean 'shape.circle'? valid node types are: (shape.circle ...)".
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph {

/// Levenshtein distance (insert, delete, substitute), for suggestions.
std::size_t edit_distance(std::string_view a, std::string_view b);

/// The closest candidate within a distance that makes sense for the name's length, or "".
std::string closest_match(std::string_view name, const std::vector<std::string>& candidates);

/// "unknown <what> '<name>'; did you mean '<x>'? valid <what>s are: (a b c)"
std::string unknown_name_message(std::string_view what, std::string_view name,
                                 const std::vector<std::string>& candidates);

}  // namespace mechgraph
