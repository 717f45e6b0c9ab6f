// Flat-faced tappet on the fixed axis +y (docs/methods/followers.md, "Translating flat face"): the
// face at s = r0 + h from the cam centre along u(phi); the contour is the envelope of the faces,
// P = s u + h' t, the contact h' from the axis along the face; rho = r0 + h + h''. The cam's frame:
// u(phi) = (sigma sin phi, cos phi), t = du/dphi = (sigma cos phi, -sin phi), sigma = +1 ccw, -1 cw.
#include "follower_types.hpp"

#include <cmath>

namespace mechgraph::followers {
namespace {

class TranslatingFlat final : public Follower {
 public:
  std::string_view type_name() const override { return "follower.flat"; }
  std::string describe() const override { return "flat-faced tappet"; }
  double roller_radius() const override { return 0.0; }
  bool pivoted() const override { return false; }
  double cam_lever(double) const override { return 0.0; }
  FollowerContact contact(double phi, const LiftDerivatives& d, double r0, bool clockwise) const override {
    const double sigma = clockwise ? -1.0 : 1.0;
    const double ux = sigma * std::sin(phi), uy = std::cos(phi);
    const double tx = sigma * std::cos(phi), ty = -std::sin(phi);
    const double s = r0 + d.lift;
    FollowerContact c;
    c.x = c.pitch_x = s * ux + d.velocity * tx;
    c.y = c.pitch_y = s * uy + d.velocity * ty;
    c.curvature_radius = s + d.acceleration;
    c.face_position = d.velocity;
    return c;
  }
};

}  // namespace

std::shared_ptr<const Follower> make_flat() { return std::make_shared<const TranslatingFlat>(); }

}  // namespace mechgraph::followers
