#pragma once
// Springs: a SpringModel (material, geometry rules and limits, not yet sized) sizes a Spring for a
// required line; the Spring then behaves as one (docs/methods/valvetrain.md, stage 4).
//
// Contract
//  - Deflection x [m] is counted from the installed length: x = 0 with the valve closed, x = stroke
//    at full lift. The line a spring is sized for is F(x) = preload + rate x on 0 <= x <= stroke.
//  - SpringModel::size(line) returns a spring whose force() reproduces the line on [0, stroke] (to
//    rounding), or throws NodeError naming the model's parameter and the limit it broke: coils
//    fewer than two, coils going solid before stroke + clearance, stress over the allowable, an
//    inner coil that does not fit. The spring index range is the model's parameter range, checked
//    when the scene loads. Models never return a spring outside their limits.
//  - Spring: force and stiffness over deflection, total mass, the share of that mass that moves
//    with the valve (`effective_mass`, a third for a uniform coil), the lowest surge (coil
//    resonance) frequency in Hz, the highest corrected shear stress over its coils at a deflection,
//    and the geometry of each coil (one for a plain spring, more for nested ones).
//  - Implementations are immutable and thread-safe.
//
// Who checks what: the model refuses what it cannot make (NodeError, above); the host checks the
// handle's kind; the conformance kit (mechgraph/testing/domain_conformance.hpp) checks that a sized
// spring reproduces its line, that stiffness is the force's derivative, that the stress stays within
// the allowable over the stroke and that the coil geometry is consistent.
#include <mechgraph/value.hpp>

#include <algorithm>
#include <limits>
#include <memory>
#include <string_view>
#include <vector>

namespace mechgraph {

/// The line a spring must give: F(x) = preload + rate x for 0 <= x <= stroke (valve side).
struct SpringLine {
  double preload = 0.0;  // N, force with the valve closed (P0)
  double rate = 0.0;     // N/m (c)
  double stroke = 0.0;   // m, full valve lift (h_max)
  double max_force() const { return preload + rate * stroke; }  // P_max
};

/// One helical coil of a sized spring.
struct CoilGeometry {
  double wire_diameter = 0.0;  // d, m
  double mean_diameter = 0.0;  // D, m
  double active_coils = 0.0;   // i (real-valued)
  double total_coils = 0.0;    // i + inactive end coils
  double solid_length = 0.0;   // m
  double free_length = 0.0;    // m
  double rate = 0.0;           // N/m
};

class MECHGRAPH_INTERFACE Spring : public DomainObject {
 public:
  ~Spring() override;  // out of line (key function, sdk/src/interfaces.cpp)
  static constexpr std::string_view kind_name = "spring";
  std::string_view kind() const override { return kind_name; }

  virtual double force(double x) const = 0;      // N at deflection x from the installed length
  virtual double stiffness(double x) const = 0;  // dF/dx, N/m
  virtual double stroke() const = 0;             // m, the working deflection it was sized for
  virtual double mass() const = 0;               // kg, whole spring
  virtual double effective_mass() const { return mass() / 3.0; }  // kg moving with the valve
  virtual double surge_frequency() const = 0;    // Hz, lowest
  virtual double stress(double x) const = 0;     // Pa, highest corrected shear stress at x
  virtual double allowable_stress() const = 0;   // Pa
  virtual std::vector<CoilGeometry> coils() const = 0;

  double preload() const { return force(0.0); }
  double max_force() const { return force(stroke()); }
  /// The deflection (from the installed length) at which the first coil goes solid, from the coil
  /// geometry: the coils share one installed length L = (sum c_k L0_k - P0) / sum c_k (free
  /// lengths L0_k, rates c_k), and coil k is solid at L - Ls_k. +inf for a spring without coils.
  double solid_deflection() const {
    double rate_sum = 0.0, weighted_free = 0.0;
    const std::vector<CoilGeometry> all = coils();
    for (const CoilGeometry& c : all) {
      rate_sum += c.rate;
      weighted_free += c.rate * c.free_length;
    }
    if (all.empty() || !(rate_sum > 0.0)) return std::numeric_limits<double>::infinity();
    const double installed = (weighted_free - preload()) / rate_sum;
    double solid = std::numeric_limits<double>::infinity();
    for (const CoilGeometry& c : all) solid = std::min(solid, installed - c.solid_length);
    return solid;
  }
};

class MECHGRAPH_INTERFACE SpringModel : public DomainObject {
 public:
  ~SpringModel() override;  // out of line (key function, sdk/src/interfaces.cpp)
  static constexpr std::string_view kind_name = "spring_model";
  std::string_view kind() const override { return kind_name; }

  /// The node type that made the model ("spring.helical"), for messages.
  virtual std::string_view type_name() const = 0;
  /// A spring that gives `line`; throws NodeError (parameter of the model, limit) if none can.
  virtual std::shared_ptr<const Spring> size(const SpringLine& line) const = 0;
};

}  // namespace mechgraph
