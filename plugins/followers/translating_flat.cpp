// follower.flat: the flat-faced tappet translating along +y, the SDK's reference implementation
// (mechgraph/domain/translating_followers.hpp; docs/methods/followers.md, "Translating flat face").
#include "follower_types.hpp"

#include <mechgraph/domain/translating_followers.hpp>

namespace mechgraph::followers {

std::shared_ptr<const Follower> make_flat() { return std::make_shared<const reference::TranslatingFlat>(); }

}  // namespace mechgraph::followers
