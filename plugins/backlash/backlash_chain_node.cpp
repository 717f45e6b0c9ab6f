// backlash.chain: the free play of the steering drive's kinematic chain, reduced to the actuator
// rod and to the nozzle's swivel axis (docs/methods/backlash.md, steps 3-4, and the
// extensions listed there: RSS, Monte Carlo of the truncated play, geometry, compliance).
//
// Every play is peak to peak: the travel between the two contact sides (a fit's clearance is
// hole minus shaft diameter). For joint i with play terms t (each max(0, sum_j s_j X_j)):
//   S_i  = sum_t max(0, mean_t)                    mean play (the source's mean clearance,
//                                                  clipped at 0 for interference)
//   dS_i = sum_t (max(0, upper_t) - max(0, mean_t)) its worst-case limit deviation; for a clearance
//                                                  fit this is the source's dA_hole + dA_shaft, and
//                                                  S_i + dS_i is always the worst-case maximum play
//   L  = L_act + sum_i k_i S_i,   dL = dL_act + sum_i k_i dS_i          (step 3, worst case)
//   delta = L/|R|,  d_delta = dL/|R|,  delta_max = (L + dL)/|R|         (step 4, radians)
// RSS: sigma_L^2 = (dL_act/3)^2 + sum_i k_i^2 sum_t sigma_t^2, sigma_t the untruncated term's
// sqrt(sum s_j^2 sigma_j^2) (0 for a term that is interference throughout); max = L + 3 sigma_L.
// Monte Carlo: each X_j from its distribution, each term max(0, .), the actuator's backlash
// normal with mean L_act and limit deviation dL_act = 3 sigma, clipped at 0 like any play.
// Compliance: measured play = clearance + load/stiffness, the elastic part reported apart.
#include "chain_geometry.hpp"
#include "node_types.hpp"
#include "mc_histogram.hpp"
#include "spec_limits.hpp"
#include "monte_carlo_sampler.hpp"
#include "stacking.hpp"

#include <mechgraph/domain/tolerance.hpp>

#include <cmath>
#include <sstream>

namespace mechgraph::backlash {
namespace {

constexpr const char* geometry_params[] = {"rod_attach_fixed", "rod_attach_moving", "axis_point", "axis_direction"};

struct JointSums {
  double mean = 0.0;      // S_i
  double limit = 0.0;     // dS_i
  double variance = 0.0;  // sum_t sigma_t^2
};

void check_joint(const JointPlay& joint) {
  for (const PlayTerm& t : joint.terms())
    for (const ToleranceLink& l : t.links)
      if (!std::isfinite(l.mean) || !std::isfinite(l.sensitivity) || !(l.half_range >= 0.0) ||
          !std::isfinite(l.half_range))
        throw NodeError("joints", "joint '" + joint.joint() + "', term '" + t.label + "', link '" + l.label +
                                      "': mean, sensitivity and half range must be finite, the half range >= 0");
}

JointSums sums_of(const JointPlay& joint) {
  JointSums s;
  for (const PlayTerm& t : joint.terms()) {
    const double mean = std::max(0.0, t.mean());
    s.mean += mean;
    s.limit += t.play_max() - mean;
    if (t.play_max() > 0.0) {
      const double sigma = term_sigma(t);
      s.variance += sigma * sigma;
    }
  }
  return s;
}

Vec3 point_param(const ParamSet& p, const char* name) {
  const std::vector<double>& v = p.numbers(name);
  if (v.size() != 3)
    throw NodeError(name, std::string(name) + " needs 3 values (x, y, z), got " + std::to_string(v.size()));
  for (double x : v)
    if (!std::isfinite(x)) throw NodeError(name, std::string(name) + " must be finite");
  return {v[0], v[1], v[2]};
}

class BacklashChainType final : public NodeType {
 public:
  BacklashChainType() {
    info_.type = "backlash.chain";
    info_.version = 2;  // 2: the fused sampler (other samples for a seed)
    info_.summary = "free play of the chain fixed part - actuator - nozzle, reduced to the rod and to the swivel axis: "
                    "worst case (the source), RSS, Monte Carlo of the truncated play; elastic compliance apart";
    const auto L = dim::length;
    info_.params = {
        ParamSpec::number_list("transfer_ratios", dim::none,
                               "k_i: how much of joint i's play reaches the rod's line of action (1 on the rod's line), "
                               "one per joint in the order of `joints`")
            .positive()
            .at_most(1e6)
            .because("> 0: a play reduced along the chain; <= 1e6: far past any lever"),
        ParamSpec::number("actuator_backlash", L, "L_act: mean backlash of the actuator itself (maker's data), peak to peak",
                          "um")
            .non_negative()
            .at_most(1.0)
            .because(">= 0: a play; <= 1 m: far past any actuator"),
        ParamSpec::number("actuator_backlash_limit", L,
                          "dL_act: limit deviation of the actuator's backlash (worst case; 3 sigma for RSS and Monte Carlo)",
                          "um")
            .non_negative()
            .at_most(1.0)
            .because(">= 0: a deviation; <= 1 m: far past any actuator"),
        ParamSpec::number("lever_arm", L,
                          "R: moment arm of the rod about the swivel axis (sign = sense of rotation); or give the geometry",
                          "mm")
            .optional()
            .at_least(-1e3)
            .at_most(1e3)
            .because("within 1 km either way (the sign is the sense of rotation): far past any linkage"),
        ParamSpec::number_list("rod_attach_fixed", L, "F: the rod's end on the fixed part (x, y, z); with the geometry", "mm")
            .optional(),
        ParamSpec::number_list("rod_attach_moving", L, "P: the rod's end on the nozzle (x, y, z); with the geometry", "mm")
            .optional(),
        ParamSpec::number_list("axis_point", L, "A: a point of the swivel axis (x, y, z); with the geometry", "mm").optional(),
        ParamSpec::number_list("axis_direction", dim::none, "n: direction of the swivel axis (x, y, z), any length")
            .optional(),
        ParamSpec::number("min_lever_arm", L, "smallest |R| accepted; below it the design is singular", "mm")
            .with_default(1e-3)
            .positive()
            .because("> 0: a design with a zero lever arm is singular"),
        ParamSpec::number("load", dim::force, "force on the rod while the play is measured (with compliance)", "N")
            .with_default(0.0)
            .non_negative()
            .because(">= 0: a force along the rod"),
        ParamSpec::number("stiffness", dim::stiffness,
                          "stiffness of the chain reduced to the rod, N/m (needed with compliance)", "N/mm")
            .optional()
            .positive()
            .because("> 0: a stiffness"),
        samples_param(),
        seed_param(),
        threads_param(),
        spec_param(dim::angle, "arcmin", "the angular backlash"),
        histogram_bins_param(),
    };
    info_.inputs = {PortSpec::handle("joints", std::string(JointPlay::kind_name), "the hinges' plays, in chain order")
                        .many()};
    const auto A = dim::angle;
    info_.outputs = {
        PortSpec::scalar("rod_backlash_mean", L, "L = L_act + sum k_i S_i: mean free play at the rod, peak to peak", "um"),
        PortSpec::scalar("rod_backlash_limit", L, "dL = dL_act + sum k_i dS_i: its worst-case limit deviation", "um"),
        PortSpec::scalar("rod_backlash_max", L, "L + dL: worst-case maximum free play at the rod", "um"),
        PortSpec::scalar("angular_backlash_mean", A, "delta = L/|R|: mean free play about the swivel axis, peak to peak",
                         "arcmin"),
        PortSpec::scalar("angular_backlash_limit", A, "d_delta = dL/|R|", "arcmin"),
        PortSpec::scalar("angular_backlash_max", A, "(L + dL)/|R|: worst-case maximum angular free play", "arcmin"),
        PortSpec::scalar("lever_arm", L, "R, given or from the geometry ((P - A) x u_rod) . n (signed)", "mm"),
        PortSpec::series("joint_contribution_worst_case", dim::none,
                         "k_i (S_i + dS_i) / (L + dL): share of joint i in the worst-case maximum (axis: joint index; labelled by joint)",
                         "%"),
        PortSpec::scalar("actuator_contribution_worst_case", dim::none,
                         "(L_act + dL_act) / (L + dL): the actuator's share in the worst-case maximum", "%"),
        PortSpec::series("joint_contribution_rss", dim::none,
                         "k_i^2 sigma_i^2 / sigma_L^2: share of joint i in the RSS variance (axis: joint index; labelled by joint)", "%"),
        PortSpec::scalar("rod_backlash_rss_sigma", L,
                         "sigma_L = sqrt((dL_act/3)^2 + sum k_i^2 sigma_i^2), each term's sigma from its links", "um"),
        PortSpec::scalar("rod_backlash_rss_max", L, "L + 3 sigma_L", "um"),
        PortSpec::scalar("angular_backlash_rss_max", A, "(L + 3 sigma_L)/|R|", "arcmin"),
        PortSpec::scalar("rod_backlash_mc_mean", L, "Monte Carlo mean of the truncated rod play (with monte_carlo)", "um"),
        PortSpec::scalar("rod_backlash_mc_sigma", L, "Monte Carlo standard deviation of the rod play (with monte_carlo)",
                         "um"),
        PortSpec::scalar("rod_backlash_mc_q999", L, "Monte Carlo 99.865 % quantile of the rod play (with monte_carlo)", "um"),
        PortSpec::scalar("angular_backlash_mc_mean", A, "rod_backlash_mc_mean/|R| (with monte_carlo)", "arcmin"),
        PortSpec::scalar("angular_backlash_mc_q999", A, "rod_backlash_mc_q999/|R| (with monte_carlo)", "arcmin"),
        PortSpec::scalar("mc_mean_error", L, "standard error of rod_backlash_mc_mean, sigma/sqrt(N) (with monte_carlo)",
                         "um"),
        PortSpec::scalar("rod_elastic_deflection", L, "load/stiffness, the elastic part apart from free play (with compliance)",
                         "um"),
        PortSpec::scalar("rod_total_under_load", L,
                         "measured play = clearance + load/stiffness: (L + dL) + load/stiffness (with compliance)", "um"),
        PortSpec::scalar("angular_total_under_load", A, "rod_total_under_load/|R| (with compliance)", "arcmin"),
    };
    for (PortSpec& port : spec_outputs(true)) info_.outputs.push_back(std::move(port));
    info_.outputs.push_back(mc_histogram_port("the angular backlash"));
    info_.effects = {
        {monte_carlo_effect, "sample every fit's hole and shaft (samples, seed), each play term truncated at zero, and "
                             "the actuator's backlash as normal with dL_act = 3 sigma, clipped at zero: the statistics "
                             "of the free play without linearisation",
         {"rod_backlash_mc_mean", "rod_backlash_mc_sigma", "rod_backlash_mc_q999", "angular_backlash_mc_mean",
          "angular_backlash_mc_q999", "mc_mean_error", "mc_out_of_spec", "mc_out_of_spec_error", "mc_cp", "mc_cpk",
          "mc_histogram"},
         {"samples", "seed", "threads", "histogram_bins"}},
        {compliance_effect, "elastic deflection load/stiffness of the chain under the measuring load, reported apart "
                            "from the free play: measured play = clearance + load/stiffness",
         {"rod_elastic_deflection", "rod_total_under_load", "angular_total_under_load"},
         {"load", "stiffness"}},
    };
    info_.work_counters = {"samples", "chunks"};
    info_.output_dependencies = {{"lever_arm", {}}};
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext& ctx) const override {
    const std::size_t n = in.count("joints");
    const std::vector<double>& k = p.numbers("transfer_ratios");
    if (k.size() != n)
      throw NodeError("transfer_ratios", "transfer_ratios has " + std::to_string(k.size()) + " values for " +
                                             std::to_string(n) + " joints: give one ratio per joint, in the order of `joints`");
    for (double ki : k)
      if (!(ki > 0.0) || !std::isfinite(ki)) throw NodeError("transfer_ratios", "every transfer ratio must be > 0 and finite");
    const double act_mean = p.number("actuator_backlash");
    const double act_limit = p.number("actuator_backlash_limit");
    if (!(act_mean >= 0.0) || !std::isfinite(act_mean))
      throw NodeError("actuator_backlash", "actuator_backlash must be >= 0 and finite");
    if (!(act_limit >= 0.0) || !std::isfinite(act_limit))
      throw NodeError("actuator_backlash_limit", "actuator_backlash_limit must be >= 0 and finite");
    const double R = lever_arm(p);
    const double arm = std::abs(R);

    std::vector<std::shared_ptr<const JointPlay>> joints;
    for (std::size_t i = 0; i < n; ++i) {
      joints.push_back(in.handle<JointPlay>("joints", i));
      check_joint(*joints.back());
    }

    // Steps 3-4 of the source, and the RSS beside them.
    const double act_sigma = act_limit / 3.0;
    double mean = act_mean, limit = act_limit, variance = act_sigma * act_sigma;
    std::vector<double> joint_max(n), joint_variance(n);
    for (std::size_t i = 0; i < n; ++i) {
      const JointSums s = sums_of(*joints[i]);
      mean += k[i] * s.mean;
      limit += k[i] * s.limit;
      joint_max[i] = k[i] * (s.mean + s.limit);
      joint_variance[i] = k[i] * k[i] * s.variance;
      variance += joint_variance[i];
    }
    const double max = mean + limit;
    const double sigma = std::sqrt(variance);
    std::vector<double> share_worst(n, 0.0), share_rss(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      if (max > 0.0) share_worst[i] = joint_max[i] / max;
      if (variance > 0.0) share_rss[i] = joint_variance[i] / variance;
    }
    out.set_scalar("rod_backlash_mean", mean);
    out.set_scalar("rod_backlash_limit", limit);
    out.set_scalar("rod_backlash_max", max);
    out.set_scalar("angular_backlash_mean", mean / arm);
    out.set_scalar("angular_backlash_limit", limit / arm);
    out.set_scalar("angular_backlash_max", max / arm);
    out.set_scalar("lever_arm", R);
    std::vector<std::string> names;
    for (const auto& j : joints) names.push_back(j->joint());
    out.set("joint_contribution_worst_case", Value::series(indexed(std::move(share_worst), names)));
    out.set_scalar("actuator_contribution_worst_case", max > 0.0 ? (act_mean + act_limit) / max : 0.0);
    out.set("joint_contribution_rss", Value::series(indexed(std::move(share_rss), names)));
    out.set_scalar("rod_backlash_rss_sigma", sigma);
    out.set_scalar("rod_backlash_rss_max", mean + 3.0 * sigma);
    out.set_scalar("angular_backlash_rss_max", (mean + 3.0 * sigma) / arm);

    // Against the spec (an angle): the RSS model of the play, and the samples scaled to the rod.
    const SpecLimits spec = read_spec(p);
    if (!ctx.effect(monte_carlo_effect)) set_spec_outputs(out, spec, mean / arm, sigma / arm, nullptr);
    if (ctx.effect(monte_carlo_effect)) {
      PlayStack stack;
      stack.own_mean = act_mean;
      stack.own_sigma = act_sigma;
      for (std::size_t i = 0; i < n; ++i)
        for (const PlayTerm& t : joints[i]->terms()) stack.terms.push_back({k[i], t});
      const std::size_t samples = read_samples(p);
      const std::uint64_t seed = read_seed(p);
      const std::size_t bins = ctx.wanted("mc_histogram") ? static_cast<std::size_t>(p.integer("histogram_bins")) : 0;
      SamplerWork work;
      const SampleSummary mc =
          monte_carlo(sampled_stack(stack), samples, seed, spec.sample_limits(arm), bins, read_threads(p), &work);
      if (bins)
        out.set("mc_histogram", Value::table(mc_histogram_table(mc.histogram, "angular_backlash", dim::angle, "arcmin", spec,
                                                                out, arm)));
      ctx.report_work("samples", static_cast<double>(samples));
      ctx.report_work("chunks", static_cast<double>(work.chunks));
      out.note(monte_carlo_note(samples, seed, mc.mean_error));
      if (spec.given()) out.note(spec_note(mc));
      set_spec_outputs(out, spec, mean / arm, sigma / arm, &mc, arm);
      out.set_scalar("rod_backlash_mc_mean", mc.mean);
      out.set_scalar("rod_backlash_mc_sigma", mc.sigma);
      out.set_scalar("rod_backlash_mc_q999", mc.q_high);
      out.set_scalar("angular_backlash_mc_mean", mc.mean / arm);
      out.set_scalar("angular_backlash_mc_q999", mc.q_high / arm);
      out.set_scalar("mc_mean_error", mc.mean_error);
    }

    if (ctx.effect(compliance_effect)) {
      if (!p.has("stiffness"))
        throw NodeError("stiffness", "the compliance effect needs stiffness (the chain's stiffness reduced to the rod, N/m)");
      const double stiffness = p.number("stiffness");
      if (!(stiffness > 0.0) || !std::isfinite(stiffness)) throw NodeError("stiffness", "stiffness must be > 0 and finite");
      const double load = p.number("load");
      if (!(load >= 0.0) || !std::isfinite(load)) throw NodeError("load", "load must be >= 0 and finite");
      const double deflection = load / stiffness;  // Hooke: x = F / c
      if (!std::isfinite((max + deflection) / arm)) {
        std::ostringstream msg;
        msg << "load / stiffness = " << load << " N / " << stiffness << " N/m overflows: the chain would not hold the load";
        throw NodeError("stiffness", msg.str());
      }
      out.set_scalar("rod_elastic_deflection", deflection);
      out.set_scalar("rod_total_under_load", max + deflection);
      out.set_scalar("angular_total_under_load", (max + deflection) / arm);
    }
  }

 private:
  static Series indexed(std::vector<double> values, std::vector<std::string> labels) {
    Series s;
    for (std::size_t i = 0; i < values.size(); ++i) s.axis.push_back(static_cast<double>(i));
    s.values = std::move(values);
    s.axis_dimension = dim::none;
    s.labels = std::move(labels);
    return s;
  }

  // R from `lever_arm`, or from the geometry; |R| >= min_lever_arm, else the design is singular.
  static double lever_arm(const ParamSet& p) {
    const double limit = p.number("min_lever_arm");
    if (!(limit > 0.0) || !std::isfinite(limit)) throw NodeError("min_lever_arm", "min_lever_arm must be > 0 and finite");
    std::size_t given = 0;
    for (const char* g : geometry_params) given += p.has(g) ? 1 : 0;
    const std::string geometry_names = "rod_attach_fixed, rod_attach_moving, axis_point and axis_direction";
    if (p.has("lever_arm")) {
      if (given > 0) throw NodeError("lever_arm", "give either lever_arm or the geometry (" + geometry_names + "), not both");
      const double R = p.number("lever_arm");
      if (!std::isfinite(R)) throw NodeError("lever_arm", "lever_arm must be finite");
      if (std::abs(R) < limit)
        throw NodeError("lever_arm", "lever_arm |R| = " + mm_text(std::abs(R)) + " is below min_lever_arm = " +
                                         mm_text(limit) + ": the rod has (almost) no moment about the swivel axis, a singular design");
      return R;
    }
    if (given == 0) throw NodeError("lever_arm", "give lever_arm, or the geometry " + geometry_names);
    for (const char* g : geometry_params)
      if (!p.has(g)) throw NodeError(g, std::string("the geometry needs ") + g + " too (" + geometry_names + ")");
    const Vec3 fixed = point_param(p, "rod_attach_fixed");
    const Vec3 moving = point_param(p, "rod_attach_moving");
    const Vec3 axis_point = point_param(p, "axis_point");
    const Vec3 axis = point_param(p, "axis_direction");
    if (!(norm(moving - fixed) > 1e-9))
      throw NodeError("rod_attach_moving", "rod_attach_moving coincides with rod_attach_fixed: the rod has no direction");
    // The direction is normalised, so any length will do; only an exact zero (or a denormal that
    // cannot be normalised) has no direction.
    if (!(norm(axis) > 1e-300) || !std::isfinite(norm(axis)))
      throw NodeError("axis_direction", "axis_direction is the zero vector: the axis has no direction");
    const double R = moment_arm(fixed, moving, axis_point, axis);
    if (!std::isfinite(R)) throw NodeError("rod_attach_moving", "the moment arm of the geometry is not finite");
    if (std::abs(R) < limit)
      throw NodeError("rod_attach_moving",
                      "the rod's line (rod_attach_fixed -> rod_attach_moving) has a moment arm |R| = " + mm_text(std::abs(R)) +
                          " about the swivel axis (axis_point, axis_direction), below min_lever_arm = " + mm_text(limit) +
                          ": it passes (almost) through the axis or runs parallel to it, a singular design");
    return R;
  }

  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_backlash_chain_type() { return std::make_shared<const BacklashChainType>(); }

}  // namespace mechgraph::backlash
