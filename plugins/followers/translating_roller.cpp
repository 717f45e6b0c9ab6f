// follower.roller and follower.offset_roller: a roller translating on a line `offset` from the cam
// centre, the SDK's reference implementation (mechgraph/domain/translating_followers.hpp;
// docs/methods/followers.md, "Translating roller").
#include "follower_types.hpp"

#include <mechgraph/domain/translating_followers.hpp>

namespace mechgraph::followers {

std::shared_ptr<const Follower> make_roller(double roller_radius, double offset) {
  return std::make_shared<const reference::TranslatingRoller>(roller_radius, offset);
}

}  // namespace mechgraph::followers
