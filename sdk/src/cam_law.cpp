#include <mechgraph/domain/cam_law.hpp>

#include "piece_points.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

namespace mechgraph {
namespace {

std::string degrees(double rad) {
  std::ostringstream out;
  out.precision(6);
  out << rad * 180.0 / std::numbers::pi << " deg";
  return out.str();
}

// Whether the law's values at one angle keep the contract: every value finite, the lift not below
// the floor. The numbers only: the message is made by sample_message, for a refusal alone.
bool sample_ok(const LiftDerivatives& d, double lift_floor) {
  return std::isfinite(d.lift) && std::isfinite(d.velocity) && std::isfinite(d.acceleration) && std::isfinite(d.jerk) &&
         d.lift >= lift_floor;
}

std::string sample_message(const LiftDerivatives& d, double phi) {
  if (!std::isfinite(d.lift) || !std::isfinite(d.velocity) || !std::isfinite(d.acceleration) || !std::isfinite(d.jerk))
    return "a NaN or infinite lift or derivative at " + degrees(phi);
  std::ostringstream out;
  out << "a negative lift (" << d.lift << " m) at " << degrees(phi);
  return out.str();
}

// A piece needs an angle of its own: some double strictly between its ends, where it can be
// evaluated apart from its neighbours (the searches read one-sided values there,
// numerics::one_sided_point). Narrower than that it is below the resolution of a double angle.
std::string piece_message(double from, double to) {
  std::ostringstream out;
  out.precision(17);
  out << "its piece from " << from * 180.0 / std::numbers::pi << " to " << to * 180.0 / std::numbers::pi
      << " deg holds no angle of its own (the two are adjacent doubles): a piece must be wider than one ulp of its "
         "angle to be evaluated apart from its neighbours";
  return out.str();
}

}  // namespace

// The contract of docs/writing-plugins.md ("The cam_law interface"), the part cheap enough to run
// on every law a node outputs: 16 + (breakpoints + 1) evaluations. It runs on every case of a
// sweep, so the checks compare numbers only (no allocation beyond the law's breakpoints(), no
// library call): a message is written only for the check that fails.
std::string CamLaw::contract_problem() const {
  constexpr double pi = std::numbers::pi;
  const double begin = event_begin();
  const double end = event_end();
  if (!std::isfinite(begin) || !std::isfinite(end)) return "its event bounds are not finite";
  if (begin <= -pi)
    return "its event begins at " + degrees(begin) +
           ", at or before -180 deg: the event must lie inside (-180, 180) deg of cam angle with the nose at 0 "
           "(nothing is wrapped or cut off; shift the law's angles or shorten the event)";
  if (end >= pi)
    return "its event ends at " + degrees(end) +
           ", at or after 180 deg: the event must lie inside (-180, 180) deg of cam angle with the nose at 0 "
           "(nothing is wrapped or cut off; shift the law's angles or shorten the event)";
  if (!(begin < end)) return "its event is empty (begins at " + degrees(begin) + ", ends at " + degrees(end) + ")";
  const double lift = max_lift();
  if (!std::isfinite(lift) || lift <= 0.0) return "max_lift() is not a positive finite length";
  if (const double r = base_radius(); !std::isfinite(r) || r <= 0.0) return "base_radius() is not a positive finite length";
  if (const double r = roller_radius(); !std::isfinite(r) || r < 0.0) return "roller_radius() is negative or not finite";
  const std::vector<double> breaks = breakpoints();
  double previous = begin;
  for (double b : breaks) {
    if (!(b > begin && b < end))
      return "breakpoint " + degrees(b) + " is not strictly inside the event (" + degrees(begin) + ", " + degrees(end) + ")";
    if (!(b > previous)) return "breakpoints are not sorted ascending without repeats (" + degrees(b) + " after " + degrees(previous) + ")";
    if (!numerics::detail::has_interior(previous, b)) return piece_message(previous, b);
    previous = b;
  }
  if (!numerics::detail::has_interior(previous, end)) return piece_message(previous, end);
  const double lift_floor = -1e-9 * lift;
  constexpr int uniform = 16;
  for (int i = 0; i < uniform; ++i) {
    const double phi = begin + (end - begin) * (i + 0.5) / uniform;
    if (const LiftDerivatives d = evaluate_in_event(phi); !sample_ok(d, lift_floor)) return sample_message(d, phi);
  }
  double left = begin;
  for (std::size_t i = 0; i <= breaks.size(); ++i) {
    const double right = i < breaks.size() ? breaks[i] : end;
    const double phi = 0.5 * (left + right);
    if (const LiftDerivatives d = evaluate_in_event(phi); !sample_ok(d, lift_floor)) return sample_message(d, phi);
    left = right;
  }
  return {};
}

}  // namespace mechgraph
