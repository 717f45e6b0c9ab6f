#include "coil_spring.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/node.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace mechgraph::springs {

double wahl_factor(double index) { return (4.0 * index - 1.0) / (4.0 * index - 4.0) + 0.615 / index; }

double Coil::stress_at(double force) const {
  const double d = geometry.wire_diameter;
  return wahl * 8.0 * force * geometry.mean_diameter / (std::numbers::pi * d * d * d);
}

Coil size_coil(const SpringMaterial& m, double index, double end_coils, const SpringLine& line,
               const std::string& index_param) {
  constexpr double pi = std::numbers::pi;
  Coil c;
  c.line = line;
  c.wahl = wahl_factor(index);
  const double p_max = line.max_force();
  const double d = std::sqrt(8.0 * c.wahl * p_max * index / (pi * m.allowable_stress));
  const double D = index * d;
  const double i = m.shear_modulus * std::pow(d, 4) / (8.0 * D * D * D * line.rate);
  if (!(i >= 2.0)) {
    std::ostringstream msg;
    msg << "the coil for " << p_max << " N at " << line.rate * 1e-3 << " N/mm would have " << i
        << " active coils, fewer than 2: lower " << index_param << " (now " << index
        << "; active coils grow as 1/index^3) or ask for a softer line";
    throw NodeError(index_param, msg.str());
  }
  c.geometry.wire_diameter = d;
  c.geometry.mean_diameter = D;
  c.geometry.active_coils = i;
  c.geometry.total_coils = i + end_coils;
  c.geometry.solid_length = (i + end_coils) * d;
  c.geometry.rate = line.rate;
  c.mass = m.density * (pi * d * d / 4.0) * pi * D * (i + end_coils);
  c.surge = d / (2.0 * pi * i * D * D) * std::sqrt(m.shear_modulus / (2.0 * m.density));
  return c;
}

void finish_lengths(std::vector<Coil>& coils, const CoilRules& rules, double stroke, std::string_view type) {
  double longest_solid = 0.0;
  for (const Coil& c : coils) longest_solid = std::max(longest_solid, c.geometry.solid_length);
  double installed = rules.installed_length;
  const double needed = longest_solid + rules.coil_clearance + stroke;
  if (installed <= 0.0) {
    installed = needed;  // the shortest installation that keeps the clearance at full lift
  } else if (installed < needed) {
    std::ostringstream msg;
    msg << std::string(type) << ": the coils go solid before full lift + clearance: solid length " << longest_solid * 1e3
        << " mm + clearance " << rules.coil_clearance * 1e3 << " mm + lift " << stroke * 1e3 << " mm = " << needed * 1e3
        << " mm exceeds the installed length " << installed * 1e3 << " mm";
    throw NodeError("installed_length", msg.str());
  }
  for (Coil& c : coils) c.geometry.free_length = installed + c.line.preload / c.line.rate;
}

CoilSpring::CoilSpring(std::vector<Coil> coils, double allowable_stress)
    : coils_(std::move(coils)), allowable_(allowable_stress), stroke_(coils_.front().line.stroke) {}

double CoilSpring::force(double x) const {
  double f = 0.0;
  for (const Coil& c : coils_) f += c.line.preload + c.line.rate * x;
  return f;
}

double CoilSpring::stiffness(double) const {
  double k = 0.0;
  for (const Coil& c : coils_) k += c.line.rate;
  return k;
}

double CoilSpring::mass() const {
  double m = 0.0;
  for (const Coil& c : coils_) m += c.mass;
  return m;
}

double CoilSpring::surge_frequency() const {
  double f = std::numeric_limits<double>::infinity();
  for (const Coil& c : coils_) f = std::min(f, c.surge);
  return f;
}

double CoilSpring::stress(double x) const {
  double s = 0.0;
  for (const Coil& c : coils_) s = std::max(s, c.stress_at(c.line.preload + c.line.rate * x));
  return s;
}

std::vector<CoilGeometry> CoilSpring::coils() const {
  std::vector<CoilGeometry> out;
  for (const Coil& c : coils_) out.push_back(c.geometry);
  return out;
}

CoilRules coil_rules(const ParamSet& p) {
  CoilRules r;
  r.material = {p.number("shear_modulus"), p.number("density"), p.number("allowable_stress")};
  r.end_coils = p.number("end_coils");
  r.coil_clearance = p.number("coil_clearance");
  r.installed_length = p.has("installed_length") ? p.number("installed_length") : 0.0;
  return r;
}

std::vector<ParamSpec> coil_rule_params() {
  return {
      ParamSpec::number("shear_modulus", dim::stress, "shear modulus G of the wire", "GPa")
          .with_default(81.5e9)
          .at_least(1e9)
          .at_most(1e12)
          .because("1 GPa to 1 TPa: spring materials, from plastics to past any steel"),
      ParamSpec::number("density", dim::density, "density of the wire", "kg/m^3").with_default(7850.0).at_least(100.0).at_most(1e5).because("100 to 100,000 kg/m^3: from foams to past osmium (22,600)"),
      ParamSpec::number("allowable_stress", dim::stress, "allowable corrected shear stress at full lift", "MPa")
          .with_default(600e6)
          .at_least(1e6)
          .at_most(1e10)
          .because("1 MPa to 10 GPa: past any spring wire (about 2.5 GPa)"),
      ParamSpec::number("end_coils", dim::none, "inactive coils (closed ends)").with_default(2.0).non_negative().at_most(20.0).because(">= 0: a count; <= 20: the closed ends of a spring, not its body"),
      ParamSpec::number("coil_clearance", dim::length, "least summed gap between the coils at full lift", "mm")
          .with_default(0.5e-3)
          .non_negative()
          .at_most(1.0)
          .because(">= 0: a gap; <= 1 m: far past any coil"),
      ParamSpec::number("installed_length", dim::length,
                        "spring length with the valve closed (the space in the head); absent: the shortest that works", "mm")
          .optional()
          .positive()
          .at_most(10.0)
          .because("> 0: a length; <= 10 m: far past any valve spring"),
  };
}

}  // namespace mechgraph::springs
