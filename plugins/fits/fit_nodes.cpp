// fit.iso286 and fit.explicit (docs/methods/backlash.md, steps 1-2): the limit deviations of a
// hole and a shaft, the clearance S = hole - shaft (min = EI - es, max = ES - ei, mean from the
// parts' mean sizes A = A_nom + (dB + dH)/2), and the Fit handle joints consume.
//
// Effect `thermal`: the parts are measured at `assembly_temperature` and work at
// `operating_temperature`; each diameter D = nominal + deviation grows to D (1 + alpha dT), so a
// deviation becomes (nominal + dev)(1 + alpha dT) - nominal. With different expansion
// coefficients of hole and shaft the clearance changes by about nominal (alpha_h - alpha_s) dT.
#include "fit_nodes.hpp"

#include "iso286.hpp"

#include <mechgraph/domain/fit.hpp>

#include <sstream>
#include <stdexcept>
#include <string_view>

namespace mechgraph::fits {
namespace {

// 20 H7/g6 (ISO 286-2): hole +21/0 um, shaft -7/-20 um, the explicit fit's example deviations.
double explicit_example(std::string_view part, std::string_view side) {
  if (part == "hole") return side == "upper" ? 21e-6 : 0.0;
  return side == "upper" ? -7e-6 : -20e-6;
}

std::string millimetres(double m) {
  std::ostringstream os;
  os.precision(6);
  os << m * 1e3;
  return os.str();
}

class FitNodeType final : public NodeType {
 public:
  explicit FitNodeType(bool iso) : iso_(iso) {
    info_.type = iso ? "fit.iso286" : "fit.explicit";
    info_.summary = iso ? "hole/shaft fit from ISO 286 designations (e.g. 20 mm H11/d11): deviations and clearances"
                        : "hole/shaft fit from explicit limit deviations (the source's dB/dH): deviations and clearances";
    info_.params.push_back(ParamSpec::number("size", dim::length, "nominal diameter", "mm").positive().at_most(3.15).because("> 0: a diameter; <= 3.15 m: the end of the ISO 286 tables").with_example(20e-3));
    if (iso) {
      info_.params.push_back(ParamSpec::text("hole", "hole tolerance class, upper case: fundamental deviation + grade, e.g. H11, JS7, K6").with_example("H7"));
      info_.params.push_back(ParamSpec::text("shaft", "shaft tolerance class, lower case, e.g. d11, h9, js6, k6").with_example("g6"));
      info_.params.push_back(ParamSpec::choice("js_rounding", {"exact", "whole_micrometre"},
                                               "js7..js11 with an odd IT in um: exact +-IT/2 (ISO 286-2 tables) or rounded "
                                               "down to whole micrometres (permitted by ISO 286-1)")
                                 .with_default("exact"));
    } else {
      for (const char* part : {"hole", "shaft"})
        for (const char* side : {"upper", "lower"})
          info_.params.push_back(ParamSpec::number(std::string(part) + "_" + side, dim::length,
                                                   std::string(side) + " limit deviation of the " + part + " (signed)", "um")
                                     .at_least(-1.0)
                                     .at_most(1.0)
                                     .because("within 1 m either way: far past any fit, finite in every sum")
                                     .with_example(explicit_example(part, side)));
    }
    for (const char* part : {"hole", "shaft"})
      info_.params.push_back(distribution_param(std::string(part) + "_distribution",
                                               std::string("spread of the ") + part +
                                                   " size over its tolerance (normal: tolerance = 6 sigma)"));
    // Engineering materials lie within -1e-5 (Invar-like, some composites) and 2e-4 1/K
    // (polymers); the range leaves room either way and keeps 1 + alpha dT meaningful.
    info_.params.push_back(ParamSpec::number("hole_expansion", dim::per_kelvin, "thermal expansion coefficient of the hole's part (thermal), -1e-4 .. 1e-3 1/K", "1/K")
                               .with_default(11.5e-6)
                               .at_least(-1e-4)
                               .at_most(1e-3)
                               .because("-1e-4 to 1e-3 per K: from the most negative known solids to past any plastic"));
    info_.params.push_back(ParamSpec::number("shaft_expansion", dim::per_kelvin, "thermal expansion coefficient of the shaft (thermal), -1e-4 .. 1e-3 1/K", "1/K")
                               .with_default(11.5e-6)
                               .at_least(-1e-4)
                               .at_most(1e-3)
                               .because("-1e-4 to 1e-3 per K: from the most negative known solids to past any plastic"));
    info_.params.push_back(ParamSpec::number("assembly_temperature", dim::temperature, "temperature the sizes hold at (thermal)", "degC")
                               .with_default(293.15)
                               .positive()
                               .because("> 0 K: an absolute temperature"));
    info_.params.push_back(ParamSpec::number("operating_temperature", dim::temperature, "temperature in service (thermal)", "degC")
                               .with_default(293.15)
                               .positive()
                               .because("> 0 K: an absolute temperature"));
    info_.effects = {{"thermal", "clearances at operating temperature from the parts' different expansion"}};
    info_.outputs = {
        PortSpec::handle("fit", std::string(Fit::kind_name), "the fit, for joints"),
        PortSpec::scalar("hole_upper", dim::length, "hole upper deviation ES", "um"),
        PortSpec::scalar("hole_lower", dim::length, "hole lower deviation EI", "um"),
        PortSpec::scalar("shaft_upper", dim::length, "shaft upper deviation es", "um"),
        PortSpec::scalar("shaft_lower", dim::length, "shaft lower deviation ei", "um"),
        PortSpec::scalar("clearance_min", dim::length, "EI - es (negative: interference)", "um"),
        PortSpec::scalar("clearance_max", dim::length, "ES - ei", "um"),
        PortSpec::scalar("clearance_mean", dim::length, "mean hole size - mean shaft size", "um"),
    };
  }
  const NodeInfo& info() const override { return info_; }

  void evaluate(const ParamSet& p, const InputSet&, OutputSet& out, EvalContext& ctx) const override {
    const double size = p.number("size");
    LimitPair hole, shaft;
    std::string designation;
    if (iso_) {
      const std::string& h = p.text("hole");
      const std::string& s = p.text("shaft");
      const JsRounding rounding = p.text("js_rounding") == "exact" ? JsRounding::exact : JsRounding::whole_micrometre;
      hole = lookup(size, h, "hole", true, rounding);
      shaft = lookup(size, s, "shaft", false, rounding);
      designation = millimetres(size) + " " + h + "/" + s;
    } else {
      hole = {p.number("hole_upper"), p.number("hole_lower")};
      shaft = {p.number("shaft_upper"), p.number("shaft_lower")};
      for (const auto& [name, pair] : {std::pair{"hole", hole}, std::pair{"shaft", shaft}})
        if (pair.upper < pair.lower)
          throw NodeError(std::string(name) + "_upper", std::string("the ") + name + " upper deviation (" + millimetres(pair.upper) +
                                                            " mm) is below its lower deviation (" + millimetres(pair.lower) + " mm)");
      designation = millimetres(size) + " mm explicit";
    }
    if (ctx.effect("thermal")) {
      const double dT = p.number("operating_temperature") - p.number("assembly_temperature");
      auto grow = [&](double dev, double alpha) { return (size + dev) * (1.0 + alpha * dT) - size; };
      const double ah = p.number("hole_expansion"), as = p.number("shaft_expansion");
      // Each size is scaled by 1 + alpha dT: at or below zero the part would have shrunk to nothing
      // and the limits would swap (hole_upper < hole_lower). A growth beyond +-10 % is no longer a
      // fit's thermal correction either; both are refused naming the coefficient.
      for (const auto& [name, alpha] : {std::pair{"hole_expansion", ah}, std::pair{"shaft_expansion", as}}) {
        const double strain = alpha * dT;
        if (!(std::abs(strain) <= 0.1)) {
          std::ostringstream m;
          m << name << " x (operating_temperature - assembly_temperature) = " << alpha << " 1/K x " << dT
            << " K = " << strain << ": the part's size would change by " << strain * 100.0
            << " %, beyond the +-10 % a linear thermal expansion can stand for";
          throw NodeError(name, m.str());
        }
      }
      hole = {grow(hole.upper, ah), grow(hole.lower, ah)};
      shaft = {grow(shaft.upper, as), grow(shaft.lower, as)};
      std::ostringstream note;
      note << designation << " at " << p.number("operating_temperature") - 273.15 << " degC";
      designation = note.str();
    }
    auto fit = std::make_shared<const Fit>(designation, size, hole, shaft, distribution_from(p.text("hole_distribution"), "hole_distribution"),
                                           distribution_from(p.text("shaft_distribution"), "shaft_distribution"));
    out.set_scalar("hole_upper", hole.upper);
    out.set_scalar("hole_lower", hole.lower);
    out.set_scalar("shaft_upper", shaft.upper);
    out.set_scalar("shaft_lower", shaft.lower);
    out.set_scalar("clearance_min", fit->clearance_min());
    out.set_scalar("clearance_max", fit->clearance_max());
    out.set_scalar("clearance_mean", fit->clearance_mean());
    out.set("fit", Value::handle(std::move(fit)));
  }

 private:
  static LimitPair lookup(double size, const std::string& designation, const char* part, bool want_hole, JsRounding rounding) {
    try {
      if (iso286_is_hole(designation) != want_hole)
        throw std::invalid_argument("'" + designation + "' is a " + (want_hole ? "shaft" : "hole") + " class; " + part +
                                    " classes are " + (want_hole ? "upper case, e.g. H11" : "lower case, e.g. d11"));
      const LimitDeviations d = iso286_deviations(size, designation, rounding);
      return {d.upper, d.lower};
    } catch (const std::invalid_argument& e) {
      throw NodeError(part, e.what());
    }
  }

  bool iso_;
  NodeInfo info_;
};

}  // namespace

std::shared_ptr<const NodeType> make_iso286_fit_type() { return std::make_shared<const FitNodeType>(true); }
std::shared_ptr<const NodeType> make_explicit_fit_type() { return std::make_shared<const FitNodeType>(false); }

}  // namespace mechgraph::fits
