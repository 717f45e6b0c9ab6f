#include "contour.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include <mechgraph/errors.hpp>

namespace mechgraph::cams {

double Follower::pitch_base() const {
  const double R = base_radius + roller_radius;
  return std::sqrt(std::max(0.0, R * R - offset * offset));
}

ContactGeometry contact_at(const Follower& f, double phi, const LiftDerivatives& d) {
  // The follower axis in the cam's frame (docs/methods/valvetrain.md, "The cam contour"): a cam
  // turned by phi ccw carries u(phi) = (sin phi, cos phi) onto the fixed axis +y, one turned cw
  // u(phi) = (-sin phi, cos phi); t = du/dphi, and t' = -u in both cases.
  const double sigma = f.clockwise ? -1.0 : 1.0;
  const double ux = sigma * std::sin(phi), uy = std::cos(phi);
  const double tx = sigma * std::cos(phi), ty = -std::sin(phi);
  ContactGeometry g;
  if (f.kind == Follower::Kind::flat) {
    const double s = f.base_radius + d.lift;
    g.x = s * ux + d.velocity * tx;
    g.y = s * uy + d.velocity * ty;
    g.curvature_radius = s + d.acceleration;
    g.face_offset = d.velocity;
  } else {
    const double s = f.pitch_base() + d.lift;
    const double a = d.velocity - f.offset;  // C' = a u + s t
    const double speed = std::hypot(a, s);
    g.pitch_x = s * ux + f.offset * tx;
    g.pitch_y = s * uy + f.offset * ty;
    const double nx = (s * ux - a * tx) / speed, ny = (s * uy - a * ty) / speed;
    g.x = g.pitch_x - f.roller_radius * nx;
    g.y = g.pitch_y - f.roller_radius * ny;
    g.pressure_angle = std::atan2(a, s);
    const double cross = a * (2.0 * d.velocity - f.offset) + s * s - s * d.acceleration;
    g.curvature_radius = speed * speed * speed / cross - f.roller_radius;
  }
  return g;
}

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
  double tol;
  long& evaluations;
  ContourPoints& out;

  ContactGeometry at(double phi) {
    ++evaluations;
    return contact_at(f, phi, law.at(phi));
  }

  // How far the chord a-b strays from the curve at `m` (contour, and pitch curve for a roller).
  double stray(const ContactGeometry& a, const ContactGeometry& b, const ContactGeometry& m) const {
    double e = distance_to_segment(m.x, m.y, a.x, a.y, b.x, b.y);
    if (f.kind == Follower::Kind::roller)
      e = std::max(e, distance_to_segment(m.pitch_x, m.pitch_y, a.pitch_x, a.pitch_y, b.pitch_x, b.pitch_y));
    return e;
  }

  // Appends the points strictly after `pa` up to and including `pb`.
  void refine(double pa, const ContactGeometry& a, double pb, const ContactGeometry& b, int depth) {
    const double pm = 0.5 * (pa + pb);
    const ContactGeometry m = at(pm);
    const double e = stray(a, b, m);
    if (!std::isfinite(e)) throw NodeError("chord_error", "the contour is not finite near cam angle " + std::to_string(pm * 180.0 / std::numbers::pi) + " deg");
    bool fine = depth >= 40 || e <= tol;
    if (fine && depth < 40) {
      // The midpoint alone can sit on the chord of an S-shaped stretch: look at the quarters too.
      const ContactGeometry q1 = at(0.5 * (pa + pm)), q3 = at(0.5 * (pm + pb));
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

ContourPoints trace_contour(const CamLaw& law, const Follower& f, double chord_error, long& evaluations) {
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
  Tracer tracer{law, f, chord_error, evaluations, out};
  ContactGeometry a = tracer.at(knots.front());
  out.phi.push_back(knots.front());
  out.points.push_back(a);
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    const ContactGeometry b = tracer.at(knots[k + 1]);
    tracer.refine(knots[k], a, knots[k + 1], b, 0);
    a = b;
  }
  // The curve is closed: the point at +pi is the one at -pi.
  out.phi.pop_back();
  out.points.pop_back();
  return out;
}

}  // namespace mechgraph::cams
