#include <mechgraph/domain/cam_curves.hpp>

#include <mechgraph/numerics/piecewise.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mechgraph {

Table svaj_table(const CamLaw& law, int points) {
  const double width = law.event_end() - law.event_begin();
  const double from = std::max(-std::numbers::pi, law.event_begin() - 0.1 * width);
  const double to = std::min(std::numbers::pi, law.event_end() + 0.1 * width);
  const auto n = static_cast<std::size_t>(std::max(points, 2));
  Table t;
  t.axis = {"cam_angle", dim::angle, std::vector<double>(n), "deg"};
  t.add_channel("crank_angle", dim::angle, "deg");
  t.add_channel("lift", dim::length, "mm");
  t.add_channel("velocity", dim::length / dim::angle, "mm/deg");
  t.add_channel("acceleration", dim::length / dim::angle.pow(2), "mm/deg^2");
  t.add_channel("jerk", dim::length / dim::angle.pow(3), "mm/deg^3");
  std::vector<double>* column[5];
  for (std::size_t k = 0; k < 5; ++k) column[k] = &t.channels[k].values;
  for (auto* c : column) c->resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    // The last point exactly at `to`: no rounding past +-pi.
    const double phi = i + 1 == n ? to : from + (to - from) * static_cast<double>(i) / static_cast<double>(n - 1);
    const LiftDerivatives d = law.at(phi);
    t.axis.values[i] = phi;
    (*column[0])[i] = 2.0 * phi;
    (*column[1])[i] = d.lift;
    (*column[2])[i] = d.velocity;
    (*column[3])[i] = d.acceleration;
    (*column[4])[i] = d.jerk;
  }
  return t;
}

std::optional<LiftEvents> events_at_lift(const std::function<double(double)>& lift, std::span<const double> knots,
                                         double checking_lift, int samples, long& evaluations) {
  const std::vector<double> crossings = numerics::all_sign_changes(
      [&](double phi) { return lift(phi) - checking_lift; }, knots, samples, evaluations);
  if (crossings.empty()) return std::nullopt;
  LiftEvents e;
  e.opening = crossings.front();
  e.closing = crossings.size() > 1 ? crossings.back() : crossings.front();
  e.duration = e.closing - e.opening;
  e.centreline = 0.5 * (e.opening + e.closing);
  return e;
}

std::optional<LiftEvents> events_at_lift(const CamLaw& law, double checking_lift, int samples, long& evaluations) {
  std::vector<double> knots{law.event_begin()};
  for (double b : law.breakpoints()) knots.push_back(b);
  knots.push_back(law.event_end());
  return events_at_lift([&](double phi) { return law.at(phi).lift; }, knots, checking_lift, samples, evaluations);
}

Table events_table(const std::function<double(double)>& lift, std::span<const double> knots,
                   const std::vector<double>& checking_lifts, int samples, long& evaluations) {
  Table t;
  t.axis = {"checking_lift", dim::length, {}, "mm"};
  const char* names[8] = {"opening",       "closing",       "duration",       "centreline",
                          "crank_opening", "crank_closing", "crank_duration", "crank_centreline"};
  for (const char* n : names) t.add_channel(n, dim::angle, "deg");
  for (double h : checking_lifts) {
    std::optional<LiftEvents> e;
    if (h == 0.0) e = LiftEvents{knots.front(), knots.back(), knots.back() - knots.front(), 0.5 * (knots.front() + knots.back())};
    else e = events_at_lift(lift, knots, h, samples, evaluations);
    if (!e) continue;
    t.axis.values.push_back(h);
    const double cam[4] = {e->opening, e->closing, e->duration, e->centreline};
    for (int k = 0; k < 4; ++k) {
      t.channels[static_cast<std::size_t>(k)].values.push_back(cam[k]);
      t.channels[static_cast<std::size_t>(k + 4)].values.push_back(2.0 * cam[k]);
    }
  }
  return t;
}

}  // namespace mechgraph
