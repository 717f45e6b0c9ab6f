#include "pivoted_frame.hpp"

#include "follower_types.hpp"

#include <sstream>

namespace mechgraph::followers {

Vec2 into_cam_frame(Vec2 w, double phi, double sigma) {
  const double c = std::cos(sigma * phi), s = std::sin(sigma * phi);
  return {w.x * c + w.y * s, -w.x * s + w.y * c};
}

std::string mm(double metres) {
  std::ostringstream s;
  s << metres * 1e3 << " mm";
  return s.str();
}

}  // namespace mechgraph::followers
