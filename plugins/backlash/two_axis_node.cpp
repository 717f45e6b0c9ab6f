// backlash.two_axis: two actuators (pitch and yaw) share one nozzle; their rods' free plays
// combine through the 2x2 Jacobian J_ij = dL_i/d theta_j (docs/methods/backlash.md, "Geometry
// instead of a scalar lever arm"; the algebra is in chain_geometry.hpp).
// With both rods free by b_1, b_2 (peak to peak), the nozzle's angle about axis j can move by
//   delta_j = sum_i |(J^-1)_ji| b_i          (worst case, peak to peak),
// which is exact for the linearised chain: the reachable set of d_theta is the parallelogram
// J^-1 [-b_1/2, b_1/2] x [-b_2/2, b_2/2], and delta_j is its extent along axis j.
#include "chain_geometry.hpp"
#include "node_types.hpp"

#include <algorithm>
#include <cmath>

namespace mechgraph::backlash {
namespace {

class TwoAxisType final : public NodeType {
 public:
  TwoAxisType() {
    info_.type = "backlash.two_axis";
    info_.summary = "angular free play of a nozzle steered by two actuators, through the 2x2 Jacobian of rod lengths "
                    "over swivel angles";
    info_.params = {
        ParamSpec::number_list("jacobian", dim::length / dim::angle,
                               "J = [dL_1/dpitch, dL_1/dyaw, dL_2/dpitch, dL_2/dyaw] (row-major; row i = actuator i); "
                               "the moment arms on the diagonal when each actuator drives one axis",
                               "mm/rad"),
        ParamSpec::number("max_condition", dim::none,
                          "largest accepted condition number of J; above it the two rods (nearly) act about the same axis")
            .with_default(1000.0)
            .at_least(1.0)
            .because(">= 1: a condition number is never below 1"),
    };
    info_.inputs = {
        PortSpec::scalar("rod_backlash_1", dim::length, "free play of actuator 1's rod, peak to peak (e.g. a chain's max)",
                         "um"),
        PortSpec::scalar("rod_backlash_2", dim::length, "free play of actuator 2's rod, peak to peak", "um"),
    };
    info_.outputs = {
        PortSpec::scalar("angular_backlash_pitch", dim::angle,
                         "worst-case free play about the pitch axis (column 1 of J), sum_i |(J^-1)_1i| b_i, peak to peak",
                         "arcmin"),
        PortSpec::scalar("angular_backlash_yaw", dim::angle,
                         "worst-case free play about the yaw axis (column 2 of J), sum_i |(J^-1)_2i| b_i, peak to peak",
                         "arcmin"),
        PortSpec::scalar("condition_number", dim::none, "sigma_max/sigma_min of J"),
    };
    info_.output_dependencies = {{"condition_number", {}}};
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet& in, OutputSet& out, EvalContext&) const override {
    const std::vector<double>& j = p.numbers("jacobian");
    if (j.size() != 4)
      throw NodeError("jacobian", "jacobian needs 4 values (row-major 2x2), got " + std::to_string(j.size()));
    for (double x : j)
      if (!std::isfinite(x)) throw NodeError("jacobian", "jacobian entries must be finite");
    const Matrix2 J{j[0], j[1], j[2], j[3]};
    const double limit = p.number("max_condition");
    const double condition = condition_number(J);
    if (!(condition <= limit)) {
      throw NodeError("jacobian", "jacobian is near-singular: condition number " +
                                      (std::isfinite(condition) ? number_text(condition) : std::string("infinite")) +
                                      " is above max_condition = " + number_text(limit) +
                                      " (the two rods act about nearly the same axis)");
    }
    const double b1 = in.scalar("rod_backlash_1"), b2 = in.scalar("rod_backlash_2");
    if (!(b1 >= 0.0) || !std::isfinite(b1)) throw NodeError("rod_backlash_1", "rod_backlash_1 must be >= 0 and finite");
    if (!(b2 >= 0.0) || !std::isfinite(b2)) throw NodeError("rod_backlash_2", "rod_backlash_2 must be >= 0 and finite");
    const Matrix2 inv = inverse(J);
    const double pitch = std::abs(inv[0]) * b1 + std::abs(inv[1]) * b2;
    const double yaw = std::abs(inv[2]) * b1 + std::abs(inv[3]) * b2;
    // A well-conditioned J can still be so small (entries near 1e-308 m/rad) that its inverse
    // overflows: refused with the size, not passed on as infinity.
    if (!std::isfinite(pitch) || !std::isfinite(yaw))
      throw NodeError("jacobian", "jacobian is too small to invert in double precision (largest entry " +
                                      number_text(std::max(std::max(std::abs(j[0]), std::abs(j[1])),
                                                           std::max(std::abs(j[2]), std::abs(j[3])))) +
                                      " m/rad): the angular backlash would exceed the range of a double");
    out.set_scalar("angular_backlash_pitch", pitch);
    out.set_scalar("angular_backlash_yaw", yaw);
    out.set_scalar("condition_number", condition);
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_two_axis_type() { return std::make_shared<const TwoAxisType>(); }

}  // namespace mechgraph::backlash
