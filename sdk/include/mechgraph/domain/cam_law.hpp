#pragma once
// CamLaw: the lift of a follower over cam angle, with its first three derivatives, exactly (closed
// forms, never numerical differentiation). See docs/methods/valvetrain.md, stage 1.
//
// Contract
//  - Cam angle phi in radians, measured from the nose (phi = 0 at the top of the lift for symmetric
//    laws). The event is [event_begin(), event_end()]; outside it the lift and every derivative are
//    zero, and the law repeats every 2*pi.
//  - evaluate_in_event(phi) is only called with event_begin() < phi < event_end(); it returns
//    h [m], dh/dphi [m/rad], d2h/dphi2 [m/rad^2], d3h/dphi3 [m/rad^3].
//  - breakpoints(): the angles strictly inside the event where some derivative up to the third is
//    discontinuous, sorted ascending. Integrators and extremum searches split there. Every piece
//    (between neighbouring knots) holds at least one double of its own, and the law evaluates each
//    double strictly between two knots on the piece that holds it, so that the searches can read
//    a piece's one-sided values a few ulps inside it (numerics::one_sided_point) however narrow.
//  - higher_derivatives(phi) gives d4h/dphi4 [m/rad^4] and d5h/dphi5 [m/rad^5] inside the event for
//    laws that have them in closed form (returns false otherwise, the default). Cam synthesis
//    against an elastic drive needs them (valvetrain.polydyne_cam).
//  - max_lift() > 0 and base_radius() > 0, finite; roller_radius() >= 0.
//  - The lift is never negative and every value is finite.
//  - Implementations are immutable and thread-safe.
//
// Who checks what
//  - The host: every cam_law a node outputs goes through contract_problem() (final, below): event
//    inside (-pi, pi) and not empty, breakpoints sorted and strictly inside the event, each piece
//    wider than one ulp (a double strictly inside it), the declared
//    radii and lift, and the law sampled at 16 angles and at each piece's midpoint (finite, lift not
//    below -1e-9 * max_lift). A law that breaks it is refused with the node type's name; nothing is
//    wrapped or truncated.
//  - The conformance kit (mechgraph/testing/cam_law_conformance.hpp, `mechgraph plugin-test`): the
//    deeper checks a host cannot afford per evaluation: zero at the event's ends, continuity at the
//    breakpoints, derivatives against Richardson differences, max_lift against dense sampling.
//  - The law's node: its own parameters (ParamSpec ranges) and the geometry that depends on them.
//    An undercut contour or a too small radius of curvature is the cam node's to refuse
//    (mechgraph/domain/cam_geometry.hpp gives the curvature); the host cannot know the limits.
#include <mechgraph/value.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph {

struct LiftDerivatives {
  double lift = 0.0;          // m
  double velocity = 0.0;      // m/rad
  double acceleration = 0.0;  // m/rad^2
  double jerk = 0.0;          // m/rad^3
};

class MECHGRAPH_INTERFACE CamLaw : public DomainObject {
 public:
  ~CamLaw() override;  // out of line (key function, sdk/src/interfaces.cpp)
  static constexpr std::string_view kind_name = "cam_law";
  std::string_view kind() const override { return kind_name; }

  virtual double event_begin() const = 0;
  virtual double event_end() const = 0;
  virtual LiftDerivatives evaluate_in_event(double phi) const = 0;
  virtual std::vector<double> breakpoints() const = 0;
  virtual double max_lift() const = 0;
  virtual double base_radius() const = 0;
  /// Radius of a roller follower; 0 for a flat-faced (mushroom) tappet.
  virtual double roller_radius() const { return 0.0; }
  /// d4h/dphi4 and d5h/dphi5 at event_begin() < phi < event_end(); false if the law cannot give them.
  virtual bool higher_derivatives(double /*phi*/, double& /*d4*/, double& /*d5*/) const { return false; }
  /// Optional closed-form query: angles strictly inside the event, ascending, that cut it into runs
  /// on each of which h^(order) (order 0 = lift, 1 = velocity, 2 = acceleration) is continuous and
  /// monotone (a law knows where its derivative h^(order+1) changes sign; extra cuts are harmless).
  /// The extrema of h^(order) over any interval are then at its ends and at the cuts inside it, and
  /// each crossing of a level lies in one run, bracketed: the searches of
  /// mechgraph/domain/cam_law_runs.hpp need a few evaluations where the generic certified search
  /// interpolates every piece. Return false (the default) when the law cannot say: the generic
  /// search is used then. The conformance kit checks the runs against dense sampling and the
  /// generic search.
  virtual bool monotone_breaks(int /*order*/, std::vector<double>& /*breaks*/) const { return false; }
  /// Optional closed-form query: the integrals of the lift and of its square over [a, b],
  /// event_begin() <= a <= b <= event_end(), in m*rad and m^2*rad (a time-area through a conical
  /// seat is a polynomial of degree 2 in the lift). Return false (the default) when the law has no
  /// closed form: quadrature is used then. The conformance kit checks them against quadrature.
  virtual bool lift_integrals(double /*a*/, double /*b*/, double& /*integral*/, double& /*integral_of_square*/) const {
    return false;
  }

  /// The checks of the contract above that the host runs on every law a node outputs (sdk/src/cam_law.cpp).
  std::string contract_problem() const final;

  /// Lift and derivatives at any angle: reduced to [-pi, pi), zero outside the event.
  LiftDerivatives at(double phi) const {
    constexpr double two_pi = 2.0 * std::numbers::pi;
    if (phi < -std::numbers::pi || phi >= std::numbers::pi) phi -= two_pi * std::floor((phi + std::numbers::pi) / two_pi);
    if (phi <= event_begin() || phi >= event_end()) return {};
    return evaluate_in_event(phi);
  }
  /// event_begin(), the breakpoints, event_end(): the ends of the smooth pieces of the event, for
  /// the searches and integrals that split there.
  std::vector<double> knots() const {
    std::vector<double> k{event_begin()};
    for (double b : breakpoints()) k.push_back(b);
    k.push_back(event_end());
    return k;
  }
};

}  // namespace mechgraph
