// fit.iso286 and fit.explicit: deviations and clearances against ISO 286-2 table values and hand
// arithmetic (docs/methods/backlash.md, steps 1-2), the thermal effect against the first-order
// formula, and the errors a designer meets.
#include "test_support.hpp"

#include "fit_nodes.hpp"

#include <mechgraph/domain/fit.hpp>

#include <catch2/catch.hpp>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;

namespace {

OutputSet run(const std::shared_ptr<const NodeType>& type, const std::map<std::string, ParamValue>& params,
              std::vector<std::string> effects = {}) {
  OutputSet out;
  RecordingContext ctx(std::move(effects));
  type->evaluate(defaults_of(type->info(), params), InputSet{}, out, ctx);
  return out;
}

double um(const OutputSet& o, const std::string& port) { return o.all().at(port).as_scalar() * 1e6; }

}  // namespace

TEST_CASE("fit.iso286: 20 H11/d11 (ISO 286-2: H11 +130/0 um, d11 -65/-195 um)", "[fits]") {
  const auto o = run(fits::make_iso286_fit_type(), {{"size", ParamValue::of_number(0.020)},
                                                    {"hole", ParamValue::of_text("H11")},
                                                    {"shaft", ParamValue::of_text("d11")}});
  CHECK_THAT(um(o, "hole_upper"), WithinAbs(130.0, 1e-9));
  CHECK_THAT(um(o, "hole_lower"), WithinAbs(0.0, 1e-9));
  CHECK_THAT(um(o, "shaft_upper"), WithinAbs(-65.0, 1e-9));
  CHECK_THAT(um(o, "shaft_lower"), WithinAbs(-195.0, 1e-9));
  CHECK_THAT(um(o, "clearance_min"), WithinAbs(65.0, 1e-9));    // EI - es
  CHECK_THAT(um(o, "clearance_max"), WithinAbs(325.0, 1e-9));   // ES - ei
  CHECK_THAT(um(o, "clearance_mean"), WithinAbs(195.0, 1e-9));  // 65 - (-130)
  const auto fit = std::dynamic_pointer_cast<const Fit>(o.all().at("fit").as_handle());
  REQUIRE(fit);
  CHECK(fit->designation() == "20 H11/d11");
  const PlayTerm term = fit->clearance_term();
  CHECK_THAT(term.mean() * 1e6, WithinAbs(195.0, 1e-9));
  CHECK_THAT(term.lower() * 1e6, WithinAbs(65.0, 1e-9));   // the source: S - dS, dS = dA_hole + dA_shaft = 65 + 65
  CHECK_THAT(term.upper() * 1e6, WithinAbs(325.0, 1e-9));
}

TEST_CASE("fit.iso286: an interference fit has negative clearance and no play", "[fits]") {
  // 50 H7/p6: H7 +25/0, p6 +42/+26 -> clearance -42 .. -1 um.
  const auto o = run(fits::make_iso286_fit_type(), {{"size", ParamValue::of_number(0.050)},
                                                    {"hole", ParamValue::of_text("H7")},
                                                    {"shaft", ParamValue::of_text("p6")}});
  CHECK_THAT(um(o, "clearance_min"), WithinAbs(-42.0, 1e-9));
  CHECK_THAT(um(o, "clearance_max"), WithinAbs(-1.0, 1e-9));
  const auto fit = std::dynamic_pointer_cast<const Fit>(o.all().at("fit").as_handle());
  CHECK(fit->clearance_term().play_max() == 0.0);
}

TEST_CASE("fit.iso286: designations that do not exist or sit on the wrong part are errors", "[fits]") {
  auto type = fits::make_iso286_fit_type();
  auto attempt = [&](double size, const char* hole, const char* shaft) {
    return run(type, {{"size", ParamValue::of_number(size)}, {"hole", ParamValue::of_text(hole)}, {"shaft", ParamValue::of_text(shaft)}});
  };
  CHECK_THROWS_MATCHES(attempt(0.020, "h11", "d11"), NodeError,
                       Catch::Matchers::Predicate<NodeError>([](const NodeError& e) {
                         return e.parameter() == "hole" && std::string(e.what()).find("upper case") != std::string::npos;
                       }));
  CHECK_THROWS_WITH(attempt(0.020, "H19", "d11"), Contains("H19") || Contains("IT19"));
  CHECK_THROWS_WITH(attempt(0.020, "H11", "zz7"), Contains("zz"));
  CHECK_THROWS_WITH(attempt(4.0, "H11", "d11"), Contains("3150"));
}

TEST_CASE("fit.explicit: the source's form, with checks", "[fits]") {
  auto type = fits::make_explicit_fit_type();
  const auto o = run(type, {{"size", ParamValue::of_number(0.020)},
                            {"hole_upper", ParamValue::of_number(21e-6)},
                            {"hole_lower", ParamValue::of_number(0.0)},
                            {"shaft_upper", ParamValue::of_number(-20e-6)},
                            {"shaft_lower", ParamValue::of_number(-33e-6)}});
  CHECK_THAT(um(o, "clearance_min"), WithinAbs(20.0, 1e-9));
  CHECK_THAT(um(o, "clearance_max"), WithinAbs(54.0, 1e-9));
  CHECK_THAT(um(o, "clearance_mean"), WithinAbs(37.0, 1e-9));
  CHECK_THROWS_WITH(run(type, {{"size", ParamValue::of_number(0.020)},
                               {"hole_upper", ParamValue::of_number(0.0)},
                               {"hole_lower", ParamValue::of_number(21e-6)},
                               {"shaft_upper", ParamValue::of_number(0.0)},
                               {"shaft_lower", ParamValue::of_number(0.0)}}),
                    Contains("below its lower deviation"));
}

TEST_CASE("fit thermal effect: clearance grows by about D (alpha_hole - alpha_shaft) dT", "[fits]") {
  auto type = fits::make_iso286_fit_type();
  const std::map<std::string, ParamValue> params{{"size", ParamValue::of_number(0.020)},
                                                 {"hole", ParamValue::of_text("H7")},
                                                 {"shaft", ParamValue::of_text("g6")},
                                                 {"hole_expansion", ParamValue::of_number(23e-6)},
                                                 {"shaft_expansion", ParamValue::of_number(11.5e-6)},
                                                 {"operating_temperature", ParamValue::of_number(393.15)}};
  const auto cold = run(type, params);
  const auto hot = run(type, params, {"thermal"});
  // Each mean diameter D + dev grows by (D + dev) alpha dT; 20 H7 mean dev +10.5 um, 20 g6 -13.5 um.
  const double exact_shift = ((0.020 + 10.5e-6) * 23e-6 - (0.020 - 13.5e-6) * 11.5e-6) * 100.0 * 1e6;
  CHECK_THAT(um(hot, "clearance_mean") - um(cold, "clearance_mean"), WithinAbs(exact_shift, 1e-9));
  // and to first order D (alpha_h - alpha_s) dT = 23 um
  CHECK_THAT(um(hot, "clearance_mean") - um(cold, "clearance_mean"), WithinAbs(23.0, 0.05));
  // the minimum clearance (EI of the hole, es of the shaft) shifts by its own exact amount
  const double min_shift = ((0.020 + 0.0) * 23e-6 - (0.020 - 7e-6) * 11.5e-6) * 100.0 * 1e6;
  CHECK_THAT(um(hot, "clearance_min") - um(cold, "clearance_min"), WithinAbs(min_shift, 1e-9));
}
