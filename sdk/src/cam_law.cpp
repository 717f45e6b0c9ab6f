#include <mechgraph/domain/cam_law.hpp>

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

std::string sample_problem(const CamLaw& law, double phi, double lift_floor) {
  const LiftDerivatives d = law.evaluate_in_event(phi);
  if (!std::isfinite(d.lift) || !std::isfinite(d.velocity) || !std::isfinite(d.acceleration) || !std::isfinite(d.jerk))
    return "a NaN or infinite lift or derivative at " + degrees(phi);
  if (d.lift < lift_floor) {
    std::ostringstream out;
    out << "a negative lift (" << d.lift << " m) at " << degrees(phi);
    return out.str();
  }
  return {};
}

// A piece needs an angle of its own: some double strictly between its ends, where it can be
// evaluated apart from its neighbours (the searches read one-sided values there,
// numerics::one_sided_point). Narrower than that it is below the resolution of a double angle.
std::string piece_problem(double from, double to) {
  if (std::nextafter(from, to) < to) return {};
  std::ostringstream out;
  out.precision(17);
  out << "its piece from " << from * 180.0 / std::numbers::pi << " to " << to * 180.0 / std::numbers::pi
      << " deg holds no angle of its own (the two are adjacent doubles): a piece must be wider than one ulp of its "
         "angle to be evaluated apart from its neighbours";
  return out.str();
}

}  // namespace

// The contract of docs/writing-plugins.md ("The cam_law interface"), the part cheap enough to run
// on every law a node outputs: about 16 + (breakpoints + 1) evaluations.
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
  if (!std::isfinite(base_radius()) || base_radius() <= 0.0) return "base_radius() is not a positive finite length";
  if (!std::isfinite(roller_radius()) || roller_radius() < 0.0) return "roller_radius() is negative or not finite";
  const std::vector<double> breaks = breakpoints();
  double previous = begin;
  for (double b : breaks) {
    if (!(b > begin && b < end))
      return "breakpoint " + degrees(b) + " is not strictly inside the event (" + degrees(begin) + ", " + degrees(end) + ")";
    if (!(b > previous)) return "breakpoints are not sorted ascending without repeats (" + degrees(b) + " after " + degrees(previous) + ")";
    if (std::string p = piece_problem(previous, b); !p.empty()) return p;
    previous = b;
  }
  if (std::string p = piece_problem(previous, end); !p.empty()) return p;
  const double lift_floor = -1e-9 * lift;
  constexpr int uniform = 16;
  for (int i = 0; i < uniform; ++i) {
    const double phi = begin + (end - begin) * (i + 0.5) / uniform;
    if (std::string p = sample_problem(*this, phi, lift_floor); !p.empty()) return p;
  }
  double left = begin;
  for (std::size_t i = 0; i <= breaks.size(); ++i) {
    const double right = i < breaks.size() ? breaks[i] : end;
    if (std::string p = sample_problem(*this, 0.5 * (left + right), lift_floor); !p.empty()) return p;
    left = right;
  }
  return {};
}

}  // namespace mechgraph
