// valvetrain.masses: the valve train's moving parts reduced to the valve (train_masses.hpp).
#include "node_types.hpp"
#include "train_masses.hpp"

namespace mechgraph::valvetrain {
namespace {

class MassesType final : public NodeType {
 public:
  MassesType() {
    info_.type = "valvetrain.masses";
    info_.summary = "masses of valve, retainer, tappet, pushrod and rocker, reduced to the valve (without the spring)";
    auto mass = [](const char* name, const char* doc) {
      return ParamSpec::number(name, dim::mass, doc, "g").with_default(0.0).non_negative().at_most(100.0).because(">= 0: a mass; <= 100 kg: far past any valve-train part");
    };
    auto arm = [](const char* name, const char* doc) {
      return ParamSpec::number(name, dim::length, doc, "mm").with_default(1.0).at_least(1e-4).at_most(10.0).because("0.1 mm to 10 m: a rocker arm (the ratio of two arms divides by them)");
    };
    info_.params = {
        ParamSpec::number("valve_mass", dim::mass, "mass of the valve", "g").positive().at_most(100.0).because("> 0: the valve has mass; <= 100 kg: far past any valve").with_example(0.06),
        mass("retainer_mass", "spring retainer (plate) and keepers"),
        mass("tappet_mass", "tappet (lifter)"),
        mass("pushrod_mass", "pushrod"),
        ParamSpec::number("rocker_inertia", dim::moment_of_inertia, "moment of inertia of the rocker about its shaft", "kg*m^2")
            .with_default(0.0)
            .non_negative()
            .at_most(10.0)
            .because(">= 0: an inertia; <= 10 kg m^2: far past any rocker"),
        arm("arm_valve", "rocker arm on the valve side, l_v"),
        arm("arm_pushrod", "rocker arm on the pushrod side, l_p (rocker ratio l_v / l_p)"),
    };
    info_.outputs = {
        PortSpec::handle("masses", std::string(TrainMasses::kind_name), "the masses and arms, for spring_design and dynamics"),
        PortSpec::scalar("mass_without_spring", dim::mass, "M_ws: everything but the spring, reduced to the valve", "g"),
        PortSpec::scalar("rocker_ratio", dim::none, "l_v / l_p"),
    };
  }
  const NodeInfo& info() const override { return info_; }
  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext&) const override {
    auto m = std::make_shared<TrainMasses>();
    m->valve = p.number("valve_mass");
    m->retainer = p.number("retainer_mass");
    m->tappet = p.number("tappet_mass");
    m->pushrod = p.number("pushrod_mass");
    m->rocker_inertia = p.number("rocker_inertia");
    m->arm_valve = p.number("arm_valve");
    m->arm_pushrod = p.number("arm_pushrod");
    out.set_scalar("mass_without_spring", m->without_spring());
    out.set_scalar("rocker_ratio", m->rocker_ratio());
    out.set("masses", Value::handle(std::shared_ptr<const TrainMasses>(std::move(m))));
  }

 private:
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_masses_type() { return std::make_shared<const MassesType>(); }

}  // namespace mechgraph::valvetrain
