// joint.spherical: a pin through a radial spherical plain bearing, steel/steel, series GE..E(S)
// (methods/backlash.md; source figures 4-5).
//
// Free play along the line of action (radial to the bearing), all in series:
//   - the bearing's radial internal clearance cr, from the ISO 12240-1 group by bore
//     (spherical_clearance.cpp) or given explicitly (radial_clearance_min/_max override the
//     group): one link, mean (min+max)/2, half range (max-min)/2, sensitivity +1;
//   - each ring fit's diametral clearance (pin in the inner ring, outer ring in the housing):
//     hole +1, shaft -1; an interference (the usual press fit of a ring) contributes 0.
// The whole radial clearance appears as play along the line of action, like a pin's (play
// factor 1). The reduction of the internal clearance by press fits and temperature (the
// "operating clearance") is not modelled here.
//
// Axial internal clearance (outputs axial_play_min/_max, not part of `play`, whose line of
// action is radial): either axial_play_factor x cr, or from the sphere geometry when the scene
// gives the ball diameter dk and outer ring width C (spherical_clearance.hpp); otherwise these
// outputs are not produced.
//
// Tilt: the bearing swivels by at most its tilt angle alpha (catalogue value of the bearing,
// e.g. SKF GE 40 ES: 6 deg; small bores allow more, GE 4 E: 16 deg). The default 6 deg is the
// source's figure: above about 6 deg of nozzle deflection a spherical bearing runs out of tilt
// and a cardan is used (joint.cardan). deflection > tilt_limit is an error.
#include "node_types.hpp"
#include "spherical_clearance.hpp"

#include <numbers>
#include <sstream>

namespace mechgraph::joints {
namespace {

constexpr double deg = std::numbers::pi / 180.0;

std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

class SphericalJointType final : public NodeType {
 public:
  SphericalJointType() {
    info_.type = "joint.spherical";
    info_.summary =
        "spherical plain bearing (steel/steel, ISO 12240-1 series E): radial internal clearance by group and bore, "
        "ring fits, tilt limit, axial clearance";
    info_.params = {
        ParamSpec::number("bore", dim::length, "bore d of the bearing; selects the row of the clearance table", "mm")
            .optional()
            .positive()
            .because("> 0: a diameter")
            .with_example(20e-3),
        ParamSpec::choice("clearance_group", {"C2", "normal", "C3"},
                          "ISO 12240-1 radial internal clearance group (overridden by radial_clearance_min/_max)")
            .with_default("normal"),
        ParamSpec::number("radial_clearance_min", dim::length,
                          "least radial internal clearance from the bearing's catalogue (with radial_clearance_max; "
                          "overrides clearance_group)",
                          "um")
            .optional()
            .non_negative()
            .because(">= 0: a clearance"),
        ParamSpec::number("radial_clearance_max", dim::length,
                          "greatest radial internal clearance (with radial_clearance_min)", "um")
            .optional()
            .non_negative()
            .because(">= 0: a clearance"),
        distribution_param("clearance_distribution",
                          "how the internal clearance is spread over its range (normal: range = 6 sigma)"),
        ParamSpec::number("tilt_limit", dim::angle,
                          "permissible tilt angle alpha of the bearing (catalogue); default: the source's 6 deg", "deg")
            .with_default(6.0 * deg)
            .positive()
            .below(90.0 * deg)
            .because("> 0 and < 90 deg: a tilt of the ring on the ball"),
        ParamSpec::number("deflection", dim::angle, "tilt the joint must allow (nozzle deflection at this hinge)", "deg")
            .with_default(0.0)
            .non_negative()
            .because(">= 0: a tilt"),
        ParamSpec::number("ball_diameter", dim::length,
                          "sphere diameter dk of the inner ring (with outer_ring_width: axial clearance from geometry)",
                          "mm")
            .optional()
            .positive()
            .because("> 0: a diameter"),
        ParamSpec::number("outer_ring_width", dim::length, "outer ring width C (with ball_diameter)", "mm")
            .optional()
            .positive()
            .because("> 0: a width"),
        ParamSpec::number("axial_play_factor", dim::none,
                          "axial internal clearance / radial internal clearance, if the maker gives it "
                          "(instead of ball_diameter and outer_ring_width; at most 100)")
            .optional()
            .positive()
            .at_most(100.0)
            .because("> 0: a factor on a play; <= 100: far past any geometry"),
        joint_label_param(),
    };
    info_.inputs = {PortSpec::handle("fits", std::string(Fit::kind_name),
                                     "the ring fits (pin in the inner ring, outer ring in the housing); may be none")
                        .many()
                        .optional_port()};
    info_.outputs = joint_play_ports();
    info_.outputs.push_back(PortSpec::scalar("internal_clearance_min", dim::length,
                                             "least radial internal clearance used (table or explicit)", "um"));
    info_.outputs.push_back(PortSpec::scalar("internal_clearance_max", dim::length,
                                             "greatest radial internal clearance used (table or explicit)", "um"));
    info_.outputs.push_back(PortSpec::scalar(
        "axial_play_min", dim::length,
        "least axial internal clearance (needs axial_play_factor, or ball_diameter and outer_ring_width)", "um"));
    info_.outputs.push_back(PortSpec::scalar(
        "axial_play_max", dim::length,
        "greatest axial internal clearance (needs axial_play_factor, or ball_diameter and outer_ring_width)", "um"));
    info_.output_dependencies = {{"internal_clearance_min", {}},
                                 {"internal_clearance_max", {}},
                                 {"axial_play_min", {}},
                                 {"axial_play_max", {}}};
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext&) const override {
    check_tilt(p);
    const auto fits = connected_fits(in, "fits");

    // The bearing's radial internal clearance: explicit limits override the group.
    ClearanceRange cr;
    std::string source;
    const bool has_min = p.has("radial_clearance_min"), has_max = p.has("radial_clearance_max");
    if (has_min || has_max) {
      if (!has_min) throw NodeError("radial_clearance_min", "radial_clearance_max is given: give radial_clearance_min too");
      if (!has_max) throw NodeError("radial_clearance_max", "radial_clearance_min is given: give radial_clearance_max too");
      cr = {p.number("radial_clearance_min"), p.number("radial_clearance_max")};
      if (!(cr.min >= 0.0)) throw NodeError("radial_clearance_min", "the radial internal clearance cannot be negative");
      if (!(cr.max >= cr.min))
        throw NodeError("radial_clearance_max", "radial_clearance_max (" + number_text(cr.max * 1e6) +
                                                    " um) is below radial_clearance_min (" + number_text(cr.min * 1e6) + " um)");
      source = "radial internal clearance " + number_text(cr.min * 1e6) + "-" + number_text(cr.max * 1e6) + " um";
      if (p.has("bore")) source += ", bore " + number_text(p.number("bore") * 1e3) + " mm";
    } else {
      if (!p.has("bore"))
        throw NodeError("bore", "the bore is needed to look up the ISO 12240-1 radial internal clearance "
                                "(or give radial_clearance_min and radial_clearance_max)");
      const ClearanceGroup group = clearance_group_from(p.text("clearance_group"));
      cr = radial_internal_clearance(p.number("bore"), group);
      source = "radial internal clearance " + std::string(designation(group)) + ", bore " +
               number_text(p.number("bore") * 1e3) + " mm";
    }

    std::vector<PlayTerm> terms;
    terms.push_back({source,
                     {{source, 0.5 * (cr.min + cr.max), 0.5 * (cr.max - cr.min), 1.0,
                       distribution_from(p.text("clearance_distribution"), "clearance_distribution")}}});
    for (const auto& fit : fits) terms.push_back(fit->clearance_term());

    std::string joint = p.has("label") ? p.text("label") : "spherical plain bearing (" + source + ")";
    set_joint_play(out, std::move(joint), std::move(terms), "fits");
    out.set_scalar("internal_clearance_min", cr.min);
    out.set_scalar("internal_clearance_max", cr.max);
    set_axial_play(p, cr, out);
  }

 private:
  static void check_tilt(const ParamSet& p) {
    const double deflection = p.number("deflection"), alpha = p.number("tilt_limit");
    if (!(alpha > 0.0)) throw NodeError("tilt_limit", "the tilt limit must be positive");
    if (!(deflection >= 0.0)) throw NodeError("deflection", "the deflection must be zero or positive");
    if (deflection > alpha)
      throw NodeError("deflection", "deflection " + number_text(deflection / deg) + " deg exceeds the bearing's tilt limit alpha = " +
                                        number_text(alpha / deg) +
                                        " deg: a spherical plain bearing runs out of tilt (methods/backlash.md: above about "
                                        "6 deg use a cardan joint, joint.cardan)");
  }

  static void set_axial_play(const ParamSet& p, const ClearanceRange& cr, OutputSet& out) {
    const bool has_dk = p.has("ball_diameter"), has_c = p.has("outer_ring_width");
    if (p.has("axial_play_factor")) {
      if (has_dk || has_c)
        throw NodeError("axial_play_factor",
                        "give either axial_play_factor or ball_diameter and outer_ring_width for the axial clearance, not both");
      const double f = p.number("axial_play_factor");
      out.set_scalar("axial_play_min", f * cr.min);
      out.set_scalar("axial_play_max", f * cr.max);
      return;
    }
    if (!has_dk && !has_c) return;  // no axial data: the axial outputs are not produced
    if (!has_dk) throw NodeError("ball_diameter", "outer_ring_width is given: the axial clearance also needs ball_diameter (dk)");
    if (!has_c) throw NodeError("outer_ring_width", "ball_diameter is given: the axial clearance also needs outer_ring_width (C)");
    const double dk = p.number("ball_diameter"), C = p.number("outer_ring_width");
    out.set_scalar("axial_play_min", axial_internal_clearance(cr.min, dk, C));
    out.set_scalar("axial_play_max", axial_internal_clearance(cr.max, dk, C));
  }

  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_spherical_joint_type() { return std::make_shared<const SphericalJointType>(); }

}  // namespace mechgraph::joints
