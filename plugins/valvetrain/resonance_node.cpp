// valvetrain.resonance: the harmonic screen of the source (docs/methods/valvetrain.md, stage 4f-k).
//   omega0 = sqrt((c_s + c_d) / M_red)                natural frequency of the drive, rad/s
//   k      = floor(omega0 / w_k)                       the cam harmonic just below resonance; k+1 checked too
//   A_k    = (2/N) sum c_d x(phi_i) cos(k phi_i),  B_k = (2/N) sum c_d x(phi_i) sin(k phi_i),
//   F_k    = sqrt(A_k^2 + B_k^2)                       over one cam revolution, N samples
//   A_el   = F_k / (xi omega0),  xi = 0.107 M_red omega0 by default (lower-camshaft statistics)
//   distortion = 100 A_el / x_rms,  x_rms = sqrt((1/N) sum x(phi_i)^2)
// x is the valve lift (valve side), c_d the drive stiffness reduced to the valve.
#include "node_types.hpp"
#include "train_masses.hpp"

#include <mechgraph/domain/valve_motion.hpp>

#include <cmath>
#include <numbers>
#include <sstream>

namespace mechgraph::valvetrain {
namespace {

class ResonanceType final : public NodeType {
 public:
  ResonanceType() {
    info_.type = "valvetrain.resonance";
    info_.summary = "natural frequency of the elastic drive, the cam harmonic nearest resonance, its vibration amplitude and "
                    "the distortion of the valve motion";
    info_.params = {
        ParamSpec::number("drive_stiffness", dim::stiffness, "c_d: stiffness of the drive (tappet, pushrod, rocker) reduced to the valve",
                          "N/mm")
            .positive()
            .at_most(1e12)
            .because("> 0: a stiffness; <= 1e9 N/mm: stiffer than any steel drive")
            .with_example(4e6),
        ParamSpec::integer("samples", "samples of the lift over one cam revolution (N)")
            .with_default(3600.0)
            .at_least(16)
            .at_most(1e8)
            .because("16 to 1e8: the harmonics need at least 16 points a turn; 1e8 bounds the time")
            .as_knob(),
        ParamSpec::number("damping_coefficient", dim::mass / dim::time,
                          "xi, N*s/m; default 0.107 M_red omega0 (from 1e-3 N*s/m: undamped, the resonant amplitude "
                          "F_k / (xi omega0) has no bound)",
                          "N*s/m")
            .optional()
            .at_least(1e-3)
            .at_most(1e9)
            .because("1e-3 to 1e9 N s/m: a damper from nearly none to far past any"),
    };
    info_.inputs = {
        PortSpec::handle("valve", std::string(ValveMotion::kind_name), "the valve's motion at the speed studied"),
        PortSpec::handle("design", std::string(SpringDesign::kind_name), "the spring design (valvetrain.spring_design)"),
    };
    info_.outputs = {
        PortSpec::scalar("omega0", dim::angular_speed, "natural frequency sqrt((c_s + c_d) / M_red)", "rad/s"),
        PortSpec::scalar("natural_frequency", dim::frequency, "omega0 / 2 pi", "Hz"),
        PortSpec::scalar("harmonic", dim::none, "k = floor(omega0 / w_k)"),
        PortSpec::scalar("force_amplitude", dim::force, "F_k, the k-th harmonic of c_d x", "N"),
        PortSpec::scalar("vibration_amplitude", dim::length, "A_el = F_k / (xi omega0)", "mm"),
        PortSpec::scalar("distortion_percent", dim::none, "100 A_el / x_rms for harmonic k"),
        PortSpec::scalar("next_force_amplitude", dim::force, "F_(k+1)", "N"),
        PortSpec::scalar("next_vibration_amplitude", dim::length, "A_el for harmonic k+1", "mm"),
        PortSpec::scalar("next_distortion_percent", dim::none, "distortion for harmonic k+1"),
        PortSpec::scalar("worst_harmonic", dim::none, "k or k+1, whichever distorts more"),
        PortSpec::scalar("worst_distortion_percent", dim::none, "the larger distortion of harmonics k and k+1"),
        PortSpec::scalar("damping_coefficient", dim::mass / dim::time, "xi used", "N*s/m"),
        PortSpec::scalar("lift_rms", dim::length, "x_rms over the cam revolution", "mm"),
    };
    info_.work_counters = {"samples"};
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext& ctx) const override {
    const auto motion = in.handle<ValveMotion>("valve");
    const auto design = in.handle<SpringDesign>("design");
    const double c_d = p.number("drive_stiffness");
    const double c_s = design->spring->stiffness(0.0);
    const double M = design->reduced_mass;
    const double omega0 = std::sqrt((c_s + c_d) / M);
    const double w_k = motion->camshaft_speed();
    const double ratio = omega0 / w_k;
    if (ratio < 1.0) {
      std::ostringstream msg;
      msg << "the drive's natural frequency " << omega0 << " rad/s is below the camshaft speed " << w_k
          << " rad/s: no cam harmonic lies below resonance (raise drive_stiffness)";
      throw NodeError("drive_stiffness", msg.str());
    }
    if (ratio > 1e7) throw NodeError("drive_stiffness", "omega0 / w_k exceeds 1e7: the harmonic number would not be meaningful");
    const long k = static_cast<long>(std::floor(ratio));
    const double xi = p.has("damping_coefficient") ? p.number("damping_coefficient") : 0.107 * M * omega0;

    // One pass over the revolution: x_rms and the two harmonics' coefficients.
    const long n = p.integer("samples");
    const double two_pi = 2.0 * std::numbers::pi;
    double sum_sq = 0.0, a_k = 0.0, b_k = 0.0, a_k1 = 0.0, b_k1 = 0.0;
    for (long i = 0; i < n; ++i) {
      const double phi = -std::numbers::pi + two_pi * static_cast<double>(i) / static_cast<double>(n);
      const double x = motion->at(phi).lift;
      sum_sq += x * x;
      const double kp = std::remainder(static_cast<double>(k) * phi, two_pi);  // k phi reduced: exact phases for large k
      const double kp1 = std::remainder(static_cast<double>(k + 1) * phi, two_pi);
      a_k += x * std::cos(kp);
      b_k += x * std::sin(kp);
      a_k1 += x * std::cos(kp1);
      b_k1 += x * std::sin(kp1);
    }
    ctx.report_work("samples", static_cast<double>(n));
    const double scale = 2.0 * c_d / static_cast<double>(n);
    const double f_k = scale * std::hypot(a_k, b_k);
    const double f_k1 = scale * std::hypot(a_k1, b_k1);
    const double x_rms = std::sqrt(sum_sq / static_cast<double>(n));
    if (!(x_rms > 0.0))
      throw NodeError("samples", "no sample of the revolution falls inside the open period: raise samples (now " +
                                     std::to_string(n) + ")");
    const double amp_k = f_k / (xi * omega0);
    const double amp_k1 = f_k1 / (xi * omega0);
    const double d_k = 100.0 * amp_k / x_rms;
    const double d_k1 = 100.0 * amp_k1 / x_rms;
    out.set_scalar("omega0", omega0);
    out.set_scalar("natural_frequency", omega0 / two_pi);
    out.set_scalar("harmonic", static_cast<double>(k));
    out.set_scalar("force_amplitude", f_k);
    out.set_scalar("vibration_amplitude", amp_k);
    out.set_scalar("distortion_percent", d_k);
    out.set_scalar("next_force_amplitude", f_k1);
    out.set_scalar("next_vibration_amplitude", amp_k1);
    out.set_scalar("next_distortion_percent", d_k1);
    out.set_scalar("worst_harmonic", static_cast<double>(d_k1 > d_k ? k + 1 : k));
    out.set_scalar("worst_distortion_percent", std::max(d_k, d_k1));
    out.set_scalar("damping_coefficient", xi);
    out.set_scalar("lift_rms", x_rms);
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_resonance_type() { return std::make_shared<const ResonanceType>(); }

}  // namespace mechgraph::valvetrain
