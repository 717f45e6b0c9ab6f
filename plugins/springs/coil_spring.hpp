#pragma once
// Helical compression coils and springs made of them (docs/methods/valvetrain.md, stage 4b).
//
// One coil of spring index C = D/d, sized for its greatest force P_max and rate c:
//   Wahl factor        Kw = (4C - 1)/(4C - 4) + 0.615/C
//   wire diameter      d  = sqrt(8 Kw P_max C / (pi tau))      (stress = tau exactly at P_max)
//   mean diameter      D  = C d
//   active coils       i  = G d^4 / (8 D^3 c)                  (real-valued)
//   mass               m  = rho (pi d^2/4) pi D (i + n_end)
//   surge frequency    f1 = d / (2 pi i D^2) sqrt(G / (2 rho))  (= 1/2 sqrt(c / m_active), both ends fixed)
//   stress at force F  tau = Kw 8 F D / (pi d^3)
//   solid length       (i + n_end) d
// A spring is one coil or several nested coils deflecting together; each carries its own line.
#include <mechgraph/domain/spring.hpp>
#include <mechgraph/node.hpp>

#include <string>
#include <string_view>

#include <vector>

namespace mechgraph::springs {

struct SpringMaterial {
  double shear_modulus = 0.0;     // G, Pa
  double density = 0.0;           // rho, kg/m^3
  double allowable_stress = 0.0;  // tau, Pa
};

/// How coils are made and installed: shared by every model of this plugin.
struct CoilRules {
  SpringMaterial material;
  double end_coils = 0.0;        // inactive coils (closed and ground ends)
  double coil_clearance = 0.0;   // m, least summed gap between coils at full lift
  double installed_length = 0.0; // m, spring length with the valve closed; 0: the shortest that works
};

double wahl_factor(double index);

struct Coil {
  CoilGeometry geometry;
  SpringLine line;     // the share of the spring's line this coil carries
  double wahl = 0.0;   // Kw
  double mass = 0.0;   // kg
  double surge = 0.0;  // Hz
  double stress_at(double force) const;
};

/// A coil of index `index` carrying `line`; lengths are set by finish_lengths(). Throws NodeError
/// ("spring_index"-like parameter `index_param`) when fewer than 2 active coils result.
Coil size_coil(const SpringMaterial& material, double index, double end_coils, const SpringLine& line,
               const std::string& index_param);

/// Sets installed/free lengths of nested coils sharing one seat, and checks that none goes solid
/// before full lift + clearance (NodeError "installed_length"). `type` names the model in messages.
void finish_lengths(std::vector<Coil>& coils, const CoilRules& rules, double stroke, std::string_view type);

/// A spring of one or more coils deflecting together.
class CoilSpring final : public Spring {
 public:
  CoilSpring(std::vector<Coil> coils, double allowable_stress);
  double force(double x) const override;
  double stiffness(double x) const override;
  double stroke() const override { return stroke_; }
  double mass() const override;
  double surge_frequency() const override;
  double stress(double x) const override;
  double allowable_stress() const override { return allowable_; }
  std::vector<CoilGeometry> coils() const override;

 private:
  std::vector<Coil> coils_;
  double allowable_;
  double stroke_;
};

/// Reads the parameters every model shares (material, end coils, clearance, installed length).
CoilRules coil_rules(const ParamSet& p);
/// Their specs, for the node types' descriptions.
std::vector<ParamSpec> coil_rule_params();

}  // namespace mechgraph::springs
