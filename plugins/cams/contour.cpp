#include "contour.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include <mechgraph/errors.hpp>
#include <mechgraph/printf_number.hpp>

namespace mechgraph::cams {

double distance_to_segment(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay;
  const double L2 = dx * dx + dy * dy;
  double t = L2 > 0.0 ? ((px - ax) * dx + (py - ay) * dy) / L2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - (ax + t * dx), py - (ay + t * dy));
}

namespace {

struct Tracer {
  const CamLaw& law;
  const Follower& f;
  bool clockwise;
  double tol;
  long& evaluations;
  ContourPoints& out;

  FollowerContact at(double phi) {
    ++evaluations;
    return f.contact(phi, law.at(phi), law.base_radius(), clockwise);
  }

  // How far the chord a-b strays from the curve at `m` (contour, and pitch curve for a roller).
  double stray(const FollowerContact& a, const FollowerContact& b, const FollowerContact& m) const {
    double e = distance_to_segment(m.x, m.y, a.x, a.y, b.x, b.y);
    if (f.roller_radius() > 0.0)
      e = std::max(e, distance_to_segment(m.pitch_x, m.pitch_y, a.pitch_x, a.pitch_y, b.pitch_x, b.pitch_y));
    return e;
  }

  // Appends the points strictly after `pa` up to and including `pb`.
  void refine(double pa, const FollowerContact& a, double pb, const FollowerContact& b, int depth) {
    const double pm = 0.5 * (pa + pb);
    const FollowerContact m = at(pm);
    const double e = stray(a, b, m);
    if (!std::isfinite(e)) throw NodeError("chord_error", "the contour is not finite near cam angle " + printf_g(pm * 180.0 / std::numbers::pi) + " deg");
    bool fine = depth >= 40 || e <= tol;
    if (fine && depth < 40) {
      // The midpoint alone can sit on the chord of an S-shaped stretch: look at the quarters too.
      const FollowerContact q1 = at(0.5 * (pa + pm)), q3 = at(0.5 * (pm + pb));
      fine = stray(a, b, q1) <= tol && stray(a, b, q3) <= tol;
    }
    if (fine) {
      if (out.phi.size() >= max_contour_points) {
        std::ostringstream m;
        m << "the contour needs more than " << max_contour_points << " points for a chord error of " << tol * 1e3
          << " mm on a cam " << 2.0 * std::hypot(b.x, b.y) * 1e3 << " mm across: raise chord_error";
        throw NodeError("chord_error", m.str());
      }
      out.phi.push_back(pb);
      out.points.push_back(b);
      return;
    }
    refine(pa, a, pm, m, depth + 1);
    refine(pm, m, pb, b, depth + 1);
  }
};

}  // namespace

ContourPoints trace_contour(const CamLaw& law, const Follower& f, bool clockwise, double chord_error, long& evaluations) {
  constexpr double pi = std::numbers::pi;
  // Start pieces: the base circle cut in eight (a chord across a whole arc could look straight to
  // a midpoint test only if the arc were tiny), the event's ends and its breakpoints.
  std::vector<double> knots;
  for (int k = 0; k <= 8; ++k) knots.push_back(-pi + 2.0 * pi * k / 8.0);
  knots.push_back(law.event_begin());
  knots.push_back(law.event_end());
  for (double b : law.breakpoints()) knots.push_back(b);
  std::sort(knots.begin(), knots.end());
  knots.erase(std::unique(knots.begin(), knots.end(), [](double a, double b) { return std::abs(a - b) < 1e-12; }),
              knots.end());
  ContourPoints out;
  Tracer tracer{law, f, clockwise, chord_error, evaluations, out};
  FollowerContact a = tracer.at(knots.front());
  out.phi.push_back(knots.front());
  out.points.push_back(a);
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    const FollowerContact b = tracer.at(knots[k + 1]);
    tracer.refine(knots[k], a, knots[k + 1], b, 0);
    a = b;
  }
  // The curve is closed: the point at +pi is the one at -pi.
  out.phi.pop_back();
  out.points.pop_back();
  return out;
}

}  // namespace mechgraph::cams
