// cam.contour: where a cam law meets its follower (any follower of the followers plugin, or the
// flat or roller tappet its own parameters describe). The contour for manufacturing (points with a
// chord-error knob, written as CSV and DXF by the host), and what the follower sees at the contact:
// pressure angle, radius of curvature, Hertz line-contact stress under a load, the face a flat
// face needs; and the refusal of a pair the follower cannot follow (undercut), naming the follower
// (docs/methods/followers.md, docs/methods/valvetrain.md "Contact stress").
#include "contour.hpp"
#include "follower_drawing.hpp"
#include "registration.hpp"

#include <mechgraph/domain/translating_followers.hpp>

#include <mechgraph/domain/cam_curves.hpp>
#include <mechgraph/numerics/piecewise.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

namespace mechgraph::cams {
namespace {

// The contour and (a roller's) pitch curve drawn to scale, in the cam frame.
Presentation contour_drawing() {
  Presentation p;
  p.role = Role::drawing_to_scale;
  p.pairs = {{"x", "y", "contour", "contour", 0},
             {"pitch_x", "pitch_y", "pitch", "pitch curve", 1},
             {"follower_x", "follower_y", "follower", "follower at the nose", 2}};
  return p;
}

constexpr double pi = std::numbers::pi;

std::string mm(double m) {
  std::ostringstream s;
  s << m * 1e3 << " mm";
  return s.str();
}

// The load at the contact over cam angle: a constant, or a connected table's contact_force channel
// (linear between its points) times load_ratio. A table over the whole revolution (its gap from the
// last angle round to the first no wider than two of its steps, nor than 10 deg) wraps; one over
// less (a valve's open period) gives no load outside it: the valve sits on its seat and the cam
// turns free.
class ContactLoad {
 public:
  ContactLoad() = default;
  explicit ContactLoad(double constant) : constant_(constant), given_(true) {}
  ContactLoad(const Table& t, double ratio) : ratio_(ratio), given_(true) {
    const Table::Column* force = t.find("contact_force");
    if (!force) {
      std::string names;
      for (const auto& c : t.channels) names += (names.empty() ? "" : " ") + c.name;
      throw NodeError("forces", "the connected table has no channel 'contact_force' (it has: " + names + ")");
    }
    if (!(t.axis.dimension == dim::angle) || !(force->dimension == dim::force))
      throw NodeError("forces", "contact_force must be a force over cam angle");
    if (t.axis.values.size() < 2 || !std::is_sorted(t.axis.values.begin(), t.axis.values.end()))
      throw NodeError("forces", "the forces table needs at least two cam angles in ascending order");
    angle_ = t.axis.values;
    force_ = force->values;
    double widest = 0.0;
    for (std::size_t j = 1; j < angle_.size(); ++j) widest = std::max(widest, angle_[j] - angle_[j - 1]);
    const double gap = angle_.front() + 2.0 * pi - angle_.back();
    whole_revolution_ = gap <= 2.0 * widest && gap <= 10.0 * pi / 180.0;
  }
  /// Where a table over less than a revolution starts and ends (the load steps there), else none.
  std::vector<double> steps() const {
    if (angle_.empty() || whole_revolution_) return {};
    return {angle_.front(), angle_.back()};
  }
  bool given() const { return given_; }
  double at(double phi) const {
    if (angle_.empty()) return constant_;
    // The table spans one revolution at most: wrap phi into [first, first + 2 pi) (an angle inside
    // the table is taken as it is: the wrap could round it past the ends).
    const double first = angle_.front();
    if (phi < first || phi > angle_.back()) phi = first + std::fmod(std::fmod(phi - first, 2.0 * pi) + 2.0 * pi, 2.0 * pi);
    if (phi >= angle_.back()) return phi == angle_.back() || whole_revolution_ ? ratio_ * force_.back() : 0.0;
    const auto it = std::upper_bound(angle_.begin(), angle_.end(), phi);
    const std::size_t j = static_cast<std::size_t>(it - angle_.begin());
    const double w = (phi - angle_[j - 1]) / (angle_[j] - angle_[j - 1]);
    return ratio_ * (force_[j - 1] + w * (force_[j] - force_[j - 1]));
  }

 private:
  double constant_ = 0.0, ratio_ = 1.0;
  bool given_ = false;
  bool whole_revolution_ = true;
  std::vector<double> angle_, force_;
};

// Hertz line contact of two cylinders along `length` (Johnson, Contact Mechanics, 4.3):
// 1/R = 1/rho_cam + 1/rho_follower (a flat face: 1/rho_follower = 0), p0 = sqrt(F E* / (pi L R)).
double hertz_line_stress(double load, double inv_radius, double length, double e_star) {
  if (!(load > 0.0) || !(inv_radius > 0.0)) return 0.0;
  return std::sqrt(load / (pi * length)) * std::sqrt(e_star * inv_radius);
}

// The allowable contact stress when the scene sets none, by follower type (docs/methods/valvetrain.md,
// "Where the defaults come from"). Rolling under a roller: the surface fatigue strength of
// induction-hardened steel on steel at 1e8 cycles, 239 kpsi = 1648 MPa (Budynas & Nisbett, Shigley's
// Mechanical Engineering Design, 9th ed., ch. 6 "Surface Fatigue Strength", p. 329), a strength with no
// design factor. Sliding under a flat face: no published table value could be read; 1200 MPa is an
// assumption for hardened steel, below the rolling value.
constexpr double kRollingStressLimitDefault = 1648e6;
constexpr double kSlidingStressLimitDefault = 1200e6;

class ContourNodeType final : public NodeType, public ForecastReads {
 public:
  ContourNodeType() {
    info_.type = "cam.contour";
    // 2: a forces table over less than a revolution loads only its span; 3: the contour turned
    // the stated way (it was mirrored: an asymmetric lobe ran backwards)
    // 4: the follower is a Follower (a connected follower node, or the parameters below); the
    // undercut check lives here, for the pair, with the smallest base radius that removes it
    info_.version = 4;
    info_.summary =
        "cam contour (x, y) in the cam frame for any follower (flat, roller, offset roller, pivoted flat or roller), "
        "with its pitch curve, pressure angle, Hertz contact stress, the face a flat face needs and the undercut check "
        "of the pair";
    info_.inputs = {
        PortSpec::handle("cam", std::string(CamLaw::kind_name), "the lift law to cut (a cam node's law)"),
        PortSpec::table("forces", "a table with a contact_force channel over cam_angle (valvetrain.dynamics' curves, "
                                  "or spring_design's force_curve: no load outside its open period), times load_ratio, "
                                  "as the load on the cam; instead of load")
            .optional_port(),
        PortSpec::handle("follower", std::string(Follower::kind_name),
                         "the follower (a follower.* node); instead of the follower, roller_radius and offset parameters")
            .optional_port(),
    };
    info_.params = {
        ParamSpec::choice("follower", {"flat", "roller"},
                          "without a connected follower: flat-faced tappet or translating roller; default: the law's "
                          "own follower (roller when the law was made for one)")
            .optional(),
        ParamSpec::number("roller_radius", dim::length, "roller radius (roller; default the law's)", "mm")
            .optional()
            .at_least(1e-6)
            .at_most(1.0)
            .because("1 um to 1 m: a roller follower of a cam (a knife edge is a flat follower's limit, not a roller)"),
        ParamSpec::number("offset", dim::length,
                          "roller axis offset from the cam centre, positive to the side that lowers the pressure "
                          "angle on the rise",
                          "mm")
            .with_default(0.0),
        ParamSpec::choice("rotation", {"ccw", "cw"},
                          "direction the cam turns, seen from the front: turned by the cam angle this way from the "
                          "drawn position (nose of a symmetric lobe on +y), it lifts the follower on +y by h; cw "
                          "mirrors the contour")
            .with_default("ccw"),
        ParamSpec::number("chord_error", dim::length,
                          "largest distance between the contour (and pitch curve) and the chords between its points",
                          "mm")
            .with_default(1e-6)
            .at_least(1e-9)
            .at_most(1e-3)
            .because("1e-9 m to 1 mm: below 1 nm the chords lie under the contour's rounding, above 1 mm the drawing is no cam's")
            .as_knob(),
        ParamSpec::integer("samples", "samples per smooth piece for the peak searches (then refined by Brent)")
            .with_default(16.0)
            .at_least(8)
            .at_most(1e6)
            .because(">= 8: fewer cannot certify a piece's interpolant; <= 1e6: more only costs time")
            .as_knob(),
        ParamSpec::integer("curve_points", "points of the contact table over the event").with_default(361.0).at_least(3).at_most(1e6).because(">= 3: a curve needs its two ends and a point between; <= 1e6: bounded in memory"),
        ParamSpec::number("load", dim::force, "contact load on the cam, constant over the event (or connect forces)", "N")
            .optional()
            .non_negative()
            .at_most(1e9)
            .because(">= 0: a compressive contact force; <= 1 GN: far past any cam, stresses stay inside a double"),
        ParamSpec::number("load_ratio", dim::none,
                          "multiplies the connected forces' contact_force (e.g. the rocker ratio, valve to cam side)")
            .with_default(1.0)
            .positive()
            .because("> 0: a factor on the load"),
        ParamSpec::number("contact_length", dim::length, "length of the contact line (cam width under the follower); needed for the stress", "mm")
            .optional()
            .at_least(1e-6)
            .at_most(10.0)
            .because("1 um to 10 m: a line contact's length (Hertz divides by it)"),
        ParamSpec::number("pressure_angle_limit", dim::angle,
                          "largest |pressure angle| the design accepts; a note when max_pressure_angle exceeds it. "
                          "Default by follower: 30 deg translating, 35 deg pivoted (the common design rule, e.g. "
                          "Norton, Cam Design and Manufacturing Handbook); a translating flat face has none. Up to 90 "
                          "deg, where the follower would jam",
                          "deg")
            .optional()
            .positive()
            .below(0.5 * std::numbers::pi)
            .because("> 0 and < 90 deg: at 90 deg the follower is pushed square to its own motion"),
        ParamSpec::number("contact_stress_limit", dim::stress,
                          "largest Hertz contact pressure the materials accept; a note when max_contact_stress exceeds "
                          "it. Default under a roller (rolling, translating or pivoted): 1648 MPa, the surface fatigue "
                          "strength of induction-hardened steel on steel at 1e8 cycles, no design factor (Shigley's "
                          "Mechanical Engineering Design, 9th ed., p. 329); under a flat face (sliding, translating "
                          "or pivoted): 1200 MPa, an assumed value for hardened steel, no published table value "
                          "found. Set the value for your materials, heat treatment and life "
                          "(docs/methods/valvetrain.md)",
                          "MPa")
            .optional()
            .positive()
            .because("> 0: an allowable stress"),
        ParamSpec::number("youngs_modulus", dim::stress, "cam material", "GPa").with_default(206e9).at_least(1e6).at_most(1e13).because("1 MPa to 10 TPa: from rubber to past diamond (about 1.2 TPa)"),
        ParamSpec::number("poisson_ratio", dim::none, "cam material").with_default(0.3).at_least(0.0).below(0.5).because(">= 0 and < 0.5: 0.5 is incompressible, where 1 - nu^2 over E of the Hertz formula loses meaning for a linear solid"),
        ParamSpec::number("follower_youngs_modulus", dim::stress, "follower material (default the cam's)", "GPa")
            .optional()
            .at_least(1e6)
            .at_most(1e13)
            .because("1 MPa to 10 TPa: from rubber to past diamond (about 1.2 TPa)"),
        ParamSpec::number("follower_poisson_ratio", dim::none, "follower material (default the cam's)")
            .optional()
            .at_least(0.0)
            .below(0.5)
            .because(">= 0 and < 0.5: 0.5 is incompressible"),
    };
    info_.outputs = {
        PortSpec::table("contour", "closed contour: x, y (and pitch_x, pitch_y for a roller) in the cam frame over "
                                   "cam_angle_ccw or cam_angle_cw (named for the way the cam turns, seen from the "
                                   "front), within chord_error; written as CSV and DXF")
            .presented(contour_drawing()),
        PortSpec::table("contact", "over the event: pressure_angle, curvature_radius (of the contour), face_offset "
                                   "(flat face: where the contact lies on it), follower_angle (pivoted), load and "
                                   "contact_stress (with a load)")
            .presented(over_cam_angle().with(ChannelDecl::of("curvature_radius", dim::length).flag(channel_flag::curvature))),
        PortSpec::scalar("points", dim::none, "points of the contour"),
        PortSpec::scalar("max_pressure_angle", dim::angle, "largest |pressure angle| (0 for a flat face)", "deg"),
        PortSpec::scalar("min_face_width", dim::length,
                         "flat face: travel of the contact across the face (translating: max h' - min h'; add a margin)", "mm"),
        PortSpec::scalar("min_face_diameter", dim::length,
                         "translating flat face: a round face centred on the follower axis needs 2 max |h'| (add a margin)",
                         "mm"),
        PortSpec::scalar("max_follower_angle", dim::angle, "pivoted follower: the arm's largest turn", "deg"),
        PortSpec::scalar("undercut_margin", dim::length,
                         "how far the pair is from undercut, usable as a constraint: the least radius of curvature of "
                         "the contour where the follower needs it convex (flat face: everywhere; roller: where the pitch "
                         "curve is convex); > 0 (an undercut pair is refused)",
                         "mm"),
        PortSpec::scalar("min_convex_radius", dim::length,
                         "least radius of curvature of the contour over its convex stretches (the base circle "
                         "included, so at most the base radius)",
                         "mm"),
        PortSpec::scalar("max_concave_curvature", dim::length.pow(-1),
                         "largest curvature 1/|rho| over the contour's concave stretches, 0 when it has none (the least "
                         "concave radius is its reciprocal; a roller needs it below 1/roller_radius)",
                         "1/mm"),
        PortSpec::scalar("max_contact_stress", dim::stress, "largest Hertz contact pressure p0 (with a load)", "MPa"),
        PortSpec::scalar("max_stress_angle", dim::angle, "cam angle of the largest contact pressure", "deg").in_frame("cam"),
    };
    info_.work_counters = {"evaluations"};
    info_.frames = cam_angle_frames(false);
  }

  const NodeInfo& info() const override { return info_; }

  // The searches over the cam's pieces, the contact table's points, and the traced contour: its
  // chords within chord_error are about sqrt(8 R chord_error) long, so their number grows as
  // chord_error^(-1/2); measured, some 17000 evaluations of 2.5 us around a cam of 40 mm base
  // radius at 1e-6 m, counted here at twice that.
  std::optional<std::vector<std::string>> forecast_reads() const override {
    return std::vector<std::string>{"samples", "curve_points", "chord_error"};  // and the cam's size
  }
  std::optional<WorkForecast> forecast(const ParamSet& p, const InputSizes& sizes) const override {
    const auto cam = sizes.find("cam");
    const double pieces = cam == sizes.end() ? 16.0 : cam->second;
    const double samples = static_cast<double>(p.integer("samples"));
    const double points = static_cast<double>(p.integer("curve_points"));
    const double contour = 1e5 * std::sqrt(1e-6 / p.number("chord_error"));
    WorkForecast f;
    f.items = pieces * 400.0 * std::max(1.0, samples / 32.0) + points + contour;
    f.memory = pieces * 8192.0 + points * 128.0 + contour * 32.0;
    f.output_size = 1.0;
    f.driver = contour >= points ? "chord_error (about " + std::to_string(static_cast<long>(contour)) + " items of contour)"
                                 : "curve_points = " + std::to_string(static_cast<long>(points));
    return f;
  }

  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext& ctx) const override {
    const auto law = in.handle<CamLaw>("cam");
    const std::shared_ptr<const Follower> follower = follower_of(*law, p, in);
    const Follower& f = *follower;
    const bool clockwise = p.text("rotation") == "cw";
    const double r0 = law->base_radius();
    long evaluations = 0;
    std::vector<double> knots = law->knots();
    knots.insert(knots.begin(), -pi);
    knots.push_back(pi);
    const int samples = static_cast<int>(p.integer("samples"));
    const double worst_at = refuse_undercut(*law, f, clockwise, knots, samples, evaluations);
    // As a length: the contour's radius of curvature where the follow margin is worst. A flat
    // face's margin is -rho; a roller's 1/(rho + rr) - 1/rr falls as rho grows where the pitch
    // curve is convex and is below -1/rr where it is concave, so its worst is the least convex
    // radius. (Read off the contact, not back from the margin: 1/(margin + 1/rr) - rr lost the
    // digits of rho / rr, 3.5e-10 of a 10 m radius under a 1 um roller.)
    out.set_scalar("undercut_margin", f.contact(worst_at, law->at(worst_at), r0, clockwise).curvature_radius);
    const auto contact_at = [&](double phi, const LiftDerivatives& d) { return f.contact(phi, d, r0, clockwise); };

    ContactLoad load;
    if (in.count("forces")) {
      if (p.has("load")) throw NodeError("load", "give load or connect forces, not both");
      load = ContactLoad(in.value("forces").as_table(), p.number("load_ratio"));
    } else if (p.has("load")) {
      load = ContactLoad(p.number("load"));
    }
    if (load.given() && !p.has("contact_length"))
      throw NodeError("contact_length", "the contact stress needs contact_length (the cam width under the follower)");
    const double e_cam = p.number("youngs_modulus"), nu_cam = p.number("poisson_ratio");
    const double e_fol = p.has("follower_youngs_modulus") ? p.number("follower_youngs_modulus") : e_cam;
    const double nu_fol = p.has("follower_poisson_ratio") ? p.number("follower_poisson_ratio") : nu_cam;
    const double e_star = 1.0 / ((1.0 - nu_cam * nu_cam) / e_cam + (1.0 - nu_fol * nu_fol) / e_fol);
    const double length = p.has("contact_length") ? p.number("contact_length") : 1.0;
    const bool roller = f.roller_radius() > 0.0;
    auto stress = [&](double phi, const FollowerContact& g) {
      const double inv_r = 1.0 / g.curvature_radius + (roller ? 1.0 / f.roller_radius() : 0.0);
      return hertz_line_stress(load.at(phi), inv_r, length, e_star);
    };

    // Peaks over the whole turn: |pressure angle|, contact pressure, and h' both ways (face). The
    // load steps where a table over part of the turn starts and ends: pieces split there too.
    for (double step : load.steps())
      if (step > -pi && step < pi) knots.push_back(step);
    std::sort(knots.begin(), knots.end());
    knots.erase(std::unique(knots.begin(), knots.end()), knots.end());
    // Each function is smooth on each piece (|pressure angle| is not: both of its signs are searched).
    numerics::SmoothPieces pieces(
        [&](double phi, double* v, double*) {
          const FollowerContact g = contact_at(phi, law->at(phi));
          v[0] = g.pressure_angle;
          v[1] = load.given() ? stress(phi, g) : 0.0;
          v[2] = g.face_position;
          v[3] = 1.0 / g.curvature_radius;  // smooth through an inflection, where the radius is not
        },
        4, knots, samples);
    const numerics::Extremum pa_max = pieces.maximum(0), pa_min = pieces.minimum(0);
    const numerics::Extremum v_max = pieces.maximum(2), v_min = pieces.minimum(2);
    const numerics::Extremum peaks[4] = {
        std::abs(pa_min.value) > std::abs(pa_max.value) ? numerics::Extremum{pa_min.x, -pa_min.value} : pa_max,
        load.given() ? pieces.maximum(1) : numerics::Extremum{},
        v_max,
        {v_min.x, -v_min.value}};
    const double kappa_max = pieces.maximum(3).value, kappa_min = pieces.minimum(3).value;

    if (ctx.wanted("contour") || ctx.wanted("points")) {
      const ContourPoints c = trace_contour(*law, f, clockwise, p.number("chord_error"), evaluations);
      Table t;
      t.closed_curve = true;
      t.turns_clockwise = clockwise;
      // The axis names the direction the cam turns, so that a CSV of the contour says it too (its
      // header: cam_angle_ccw [deg] or cam_angle_cw [deg]).
      t.axis = {clockwise ? "cam_angle_cw" : "cam_angle_ccw", dim::angle, c.phi, "deg"};
      auto& x = t.add_channel("x", dim::length, "mm").values;
      x.reserve(c.points.size());
      for (const auto& g : c.points) x.push_back(g.x);
      auto& y = t.add_channel("y", dim::length, "mm").values;
      for (const auto& g : c.points) y.push_back(g.y);
      if (roller) {
        auto& px = t.add_channel("pitch_x", dim::length, "mm").values;
        for (const auto& g : c.points) px.push_back(g.pitch_x);
        auto& py = t.add_channel("pitch_y", dim::length, "mm").values;
        for (const auto& g : c.points) py.push_back(g.pitch_y);
      }
      {
        // A flat face at the width its contact sweeps (min_face_width), a pivoted one with its arm and pivot.
        FollowerDrawing drawn = draw_follower_at_nose(*law, f, c, clockwise, v_min.value, v_max.value, c.points.size());
        t.add_channel("follower_x", dim::length, "mm").values = std::move(drawn.x);
        t.add_channel("follower_y", dim::length, "mm").values = std::move(drawn.y);
      }
      // Which way the drawn contour turns (docs/methods/valvetrain.md, "The cam contour").
      if (f.pivoted())
        out.note(std::string("contour: the cam turns ") + (clockwise ? "clockwise" : "counterclockwise") +
                 " seen from the front under the " + f.named() +
                 "; the drawing is the cam at cam angle 0 with the follower above it on +y");
      else
        out.note(clockwise ? "contour: the cam turns clockwise seen from the front; in the drawing the follower axis at "
                             "cam angle phi lies phi counterclockwise from +y (nose at phi = 0)"
                           : "contour: the cam turns counterclockwise seen from the front; in the drawing the follower "
                             "axis at cam angle phi lies phi clockwise from +y (nose at phi = 0)");
      out.set_scalar("points", static_cast<double>(c.points.size()));
      out.set("contour", Value::table(std::move(t)));
    }
    evaluations += pieces.work().evaluations;
    out.set_scalar("min_convex_radius", kappa_max > 0.0 ? 1.0 / kappa_max : r0);
    out.set_scalar("max_concave_curvature", kappa_min < 0.0 ? -kappa_min : 0.0);
    out.set_scalar("max_pressure_angle", peaks[0].value);
    // The engineer's limits (or the defaults by follower type): a note when exceeded.
    const bool translating_flat = !roller && !f.pivoted();
    if (p.has("pressure_angle_limit") || !translating_flat) {
      const double limit = p.has("pressure_angle_limit") ? p.number("pressure_angle_limit") : (f.pivoted() ? 35.0 : 30.0) * pi / 180.0;
      if (peaks[0].value > limit) {
        std::ostringstream m;
        m << "pressure angle: " << peaks[0].value * 180.0 / pi << " deg at cam angle " << peaks[0].x * 180.0 / pi
          << " deg exceeds " << (p.has("pressure_angle_limit") ? "pressure_angle_limit " : "the default limit for the ")
          << (p.has("pressure_angle_limit") ? "" : f.named() + ", ") << limit * 180.0 / pi
          << " deg: the follower is pushed sideways harder than the rule accepts (larger base radius, offset, or a "
             "longer action angle lower it)";
        out.note(m.str());
      }
    }
    if (load.given()) {
      const bool own_limit = p.has("contact_stress_limit");
      const double limit = own_limit ? p.number("contact_stress_limit")
                           : roller  ? kRollingStressLimitDefault
                                     : kSlidingStressLimitDefault;
      if (peaks[1].value > limit) {
        std::ostringstream m;
        m << "contact stress: " << peaks[1].value * 1e-6 << " MPa at cam angle " << peaks[1].x * 180.0 / pi << " deg exceeds ";
        if (own_limit)
          m << "contact_stress_limit " << limit * 1e-6 << " MPa";
        else if (roller)
          m << "the default for a roller (rolling), " << limit * 1e-6
            << " MPa: induction-hardened steel on steel at 1e8 cycles (Shigley's Mechanical Engineering Design, 9th "
               "ed.); set contact_stress_limit for your materials and life";
        else
          m << "the default for a flat face (sliding), " << limit * 1e-6
            << " MPa: an assumed value for hardened steel, not a published one; set contact_stress_limit for your "
               "materials and life";
        out.note(m.str());
      }
      if (!in.count("forces")) {
        std::ostringstream m;
        m << "contact stress: from a constant load of " << p.number("load")
          << " N assumed over the whole turn (an assumption, not the valve train's force: connect forces from "
             "valvetrain.dynamics or spring_design for the load the cam carries)";
        out.note(m.str());
      }
    }
    if (!roller) {
      out.set_scalar("min_face_width", peaks[2].value + peaks[3].value);
      if (!f.pivoted()) out.set_scalar("min_face_diameter", 2.0 * std::max(peaks[2].value, peaks[3].value));
    }
    if (f.pivoted()) out.set_scalar("max_follower_angle", law->max_lift() / f.cam_lever(r0));
    if (load.given()) {
      out.set_scalar("max_contact_stress", peaks[1].value);
      out.set_scalar("max_stress_angle", peaks[1].x);
    }

    if (ctx.wanted("contact")) {
      const double width = law->event_end() - law->event_begin();
      const double from = std::max(-pi, law->event_begin() - 0.1 * width), to = std::min(pi, law->event_end() + 0.1 * width);
      const auto n = static_cast<std::size_t>(p.integer("curve_points"));
      Table t;
      t.axis = {"cam_angle", dim::angle, std::vector<double>(n), "deg"};
      t.add_channel("pressure_angle", dim::angle, "deg");
      t.add_channel("curvature_radius", dim::length, "mm");
      if (!roller) t.add_channel("face_offset", dim::length, "mm");
      if (f.pivoted()) t.add_channel("follower_angle", dim::angle, "deg");
      if (load.given()) {
        t.add_channel("load", dim::force, "N");
        t.add_channel("contact_stress", dim::stress, "MPa");
      }
      for (auto& c : t.channels) c.values.resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        const double phi = i + 1 == n ? to : from + (to - from) * static_cast<double>(i) / static_cast<double>(n - 1);
        const FollowerContact g = contact_at(phi, law->at(phi));
        ++evaluations;
        t.axis.values[i] = phi;
        std::size_t k = 0;
        t.channels[k++].values[i] = g.pressure_angle;
        t.channels[k++].values[i] = g.curvature_radius;
        if (!roller) t.channels[k++].values[i] = g.face_position;
        if (f.pivoted()) t.channels[k++].values[i] = g.follower_angle;
        if (load.given()) {
          t.channels[k++].values[i] = load.at(phi);
          t.channels[k++].values[i] = stress(phi, g);
        }
      }
      out.set("contact", Value::table(std::move(t)));
    }
    ctx.report_work("evaluations", static_cast<double>(evaluations));
  }

 private:
  // The connected follower, or the flat or translating roller the parameters describe; a law made
  // for a roller (a three-arc cam's lift is its roller centre's) must be cut for that roller.
  static std::shared_ptr<const Follower> follower_of(const CamLaw& law, const ParamSet& p, const InputSet& in) {
    const double law_roller = law.roller_radius();
    std::shared_ptr<const Follower> f;
    if (in.count("follower")) {
      for (const char* name : {"follower", "roller_radius", "offset"})
        if (p.has(name) && !(std::string(name) == "offset" && p.number("offset") == 0.0))
          throw NodeError(name, std::string(name) + " is set but a follower is connected: give the follower's "
                                                    "dimensions on its own node");
      f = in.handle<Follower>("follower");
      if (law_roller > 0.0 && (f->pivoted() || std::abs(f->roller_radius() - law_roller) > 1e-9 * law_roller))
        throw NodeError("follower", "the law's lift is that of a translating roller of radius " + mm(law_roller) +
                                        " (its cam node's follower); the " + f->named() + " cannot follow it");
      return f;
    }
    const std::string kind = p.has("follower") ? p.text("follower") : (law_roller > 0.0 ? "roller" : "flat");
    if (kind == "flat") {
      if (law_roller > 0.0)
        throw NodeError("follower", "the law's lift is that of a roller of radius " + mm(law_roller) +
                                        " (its cam node's follower); cut it for that roller, or make the law for a flat face");
      if (p.has("roller_radius")) throw NodeError("roller_radius", "roller_radius is set but follower is flat");
      return std::make_shared<const reference::TranslatingFlat>();
    }
    double rr = 0.0;
    if (p.has("roller_radius")) {
      rr = p.number("roller_radius");
      if (law_roller > 0.0 && std::abs(rr - law_roller) > 1e-9 * law_roller)
        throw NodeError("roller_radius", "roller_radius " + mm(rr) + " differs from the " + mm(law_roller) +
                                             " the law was made for");
    } else if (law_roller > 0.0) {
      rr = law_roller;
    } else {
      throw NodeError("roller_radius", "follower roller needs roller_radius");
    }
    const double offset = p.number("offset");
    if (!(std::abs(offset) < law.base_radius() + rr))
      throw NodeError("offset", "|offset| " + mm(std::abs(offset)) + " must stay below base radius + roller radius " +
                                    mm(law.base_radius() + rr));
    return std::make_shared<const reference::TranslatingRoller>(rr, offset);
  }

  // The worst follow margin of the pair over the turn (Follower::follow_margin: >= 0 undercut) for
  // base radius r0, the lift law unchanged.
  static numerics::Extremum worst_margin(const CamLaw& law, const Follower& f, bool clockwise, double r0,
                                         const std::vector<double>& knots, int samples, long& evaluations) {
    numerics::Extremum worst[1];
    numerics::maximize_piecewise_together(
        [&](double phi, double* v, double* slope) {
          v[0] = f.follow_margin(f.contact(phi, law.at(phi), r0, clockwise));
          slope[0] = std::numeric_limits<double>::quiet_NaN();
        },
        1, knots, samples, evaluations, worst);
    return worst[0];
  }

  // Undercut: a flat face needs rho > 0 everywhere; a roller needs its pitch curve's convex radius
  // above the roller's (rho_p > rr), and at a concave stretch |rho| above it too, or it cannot follow.
  // The refusal names the follower and the smallest base radius that works with this lift law
  // (grown by 1.5x, then bisected to 0.001 mm; a base radius the follower cannot sit on counts as
  // too small). Returns the cam angle of the worst follow margin of a pair that follows.
  static double refuse_undercut(const CamLaw& law, const Follower& f, bool clockwise, const std::vector<double>& knots,
                                int samples, long& evaluations) {
    const double r0 = law.base_radius();
    const numerics::Extremum worst = worst_margin(law, f, clockwise, r0, knots, samples, evaluations);
    if (!(worst.value >= 0.0)) return worst.x;
    const auto works = [&](double r) {
      try {
        return !(worst_margin(law, f, clockwise, r, knots, samples, evaluations).value >= 0.0);
      } catch (const NodeError&) {
        return false;
      }
    };
    // The base radii that work: a scan up from r0 by factors of 1.25 to 1000 r0 finds the first; its
    // lower end is bisected to 0.001 mm against the last that did not. For a pivoted follower the
    // scan goes on: a pivoted flat pad works only in a window (its pad turns too far on a large
    // cam), whose upper end is bisected too. (A window narrower than 25 % between two scan points
    // can be missed.) A translating follower's radius of curvature grows with r0: no window.
    const auto bisect = [&](double bad, double good) {
      while (std::abs(good - bad) > 1e-6) {
        const double mid = 0.5 * (bad + good);
        if (mid == bad || mid == good) break;  // neighbouring doubles: as close as it gets
        (works(mid) ? good : bad) = mid;
      }
      return good;
    };
    std::optional<double> smallest, largest;
    double previous = r0;
    // 31 steps of 1.25 reach 1000 r0 (counted, not compared: a denormal r0 times 1.25 may round to itself).
    for (int k = 1; k <= 31; ++k) {
      const double r = r0 * std::pow(1.25, k);
      if (!(r > previous)) continue;
      if (!smallest) {
        if (works(r)) smallest = bisect(previous, r);
        if (smallest && !f.pivoted()) break;
      } else if (!works(r)) {
        largest = bisect(r, previous);
        break;
      }
      previous = r;
    }
    std::ostringstream m;
    const FollowerContact g = f.contact(worst.x, law.at(worst.x), r0, clockwise);
    m << "the " << f.named() << " cannot follow this law: at cam angle " << worst.x * 180.0 / pi
      << " deg the contour's radius of curvature is " << mm(g.curvature_radius);
    if (f.roller_radius() > 0.0)
      m << " (the pitch curve's radius there is not above the roller's: undercut)";
    else
      m << " (undercut)";
    if (smallest) {
      // The limit is on the edge (and printed to 4 digits may fall below it): suggested with 1 %
      // more, rounded up to 0.1 mm, or the window's middle when the window is narrower than that.
      double suggested = std::ceil(*smallest * 1.01 * 1e4) / 1e4;
      if (largest && !(suggested < *largest)) suggested = 0.5 * (*smallest + *largest);
      if (largest)
        m << "; with this lift only base radii from " << mm(*smallest) << " to " << mm(*largest)
          << " work for this follower (it is " << mm(r0) << "); take e.g. " << mm(suggested);
      else
        m << "; with this lift the cam's base_radius must be at least " << mm(*smallest) << " for this follower (it is "
          << mm(r0) << "); take e.g. " << mm(suggested) << " (1 % above the limit, rounded up to 0.1 mm)";
    }
    m << (f.roller_radius() > 0.0 ? "; or use a smaller roller, or soften the law" : "; or soften the law");
    throw NodeError(f.roller_radius() > 0.0 ? "roller_radius" : "follower", m.str());
  }

  NodeInfo info_;
};

}  // namespace

void add_contour_type(NodeTypeList& out) { out.push_back(std::make_shared<const ContourNodeType>()); }

}  // namespace mechgraph::cams
