// joint.pin: the fits' clearances summed in series, interference giving no play
// (methods/backlash.md, steps 2-3). Limit deviations from ISO 286-2, size range 18-30 mm:
//   H11 +130/0, d11 -65/-195, h11 0/-130, H7 +21/0, k6 +15/+2, n6 +28/+15, s6 +48/+35 (um).
#include "test_support.hpp"

#include "joints/node_types.hpp"

#include <mechgraph/domain/fit.hpp>
#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

constexpr double um = 1e-6;

std::shared_ptr<const Fit> fit(const std::string& name, double es_hole, double ei_hole, double es_shaft, double ei_shaft) {
  return std::make_shared<const Fit>(name, 0.020, LimitPair{es_hole * um, ei_hole * um}, LimitPair{es_shaft * um, ei_shaft * um},
                                     Distribution::normal, Distribution::normal);
}
const auto H11_d11 = fit("20 H11/d11", 130, 0, -65, -195);  // clearance 65..325, mean 195
const auto H11_h11 = fit("20 H11/h11", 130, 0, 0, -130);    // clearance 0..260, mean 130
const auto H7_s6 = fit("20 H7/s6", 21, 0, 48, 35);          // -48..-14: interference
const auto H7_k6 = fit("20 H7/k6", 21, 0, 15, 2);           // -15..19, mean +2: transition
const auto H7_n6 = fit("20 H7/n6", 21, 0, 28, 15);          // -28..6, mean -11: transition

OutputSet run_pin(const std::vector<std::shared_ptr<const Fit>>& fits, std::map<std::string, ParamValue> params = {}) {
  auto type = joints::make_pin_joint_type();
  InputSet in;
  for (const auto& f : fits) in.add("fits", Value::handle(f));
  OutputSet out;
  RecordingContext ctx;
  type->evaluate(defaults_of(type->info(), params), in, out, ctx);
  return out;
}

double scalar(const OutputSet& o, const std::string& port) { return o.all().at(port).as_scalar(); }
std::shared_ptr<const JointPlay> play_of(const OutputSet& o) {
  return std::dynamic_pointer_cast<const JointPlay>(o.all().at("play").as_handle());
}

}  // namespace

TEST_CASE("joint.pin: one fit gives its clearance limits and mean", "[joints][pin]") {
  const OutputSet out = run_pin({H11_d11});
  CHECK_THAT(scalar(out, "play_min"), WithinRel(65 * um, 1e-12));
  CHECK_THAT(scalar(out, "play_max"), WithinRel(325 * um, 1e-12));
  CHECK_THAT(scalar(out, "play_mean"), WithinRel(195 * um, 1e-12));
  const auto play = play_of(out);
  REQUIRE(play);
  CHECK(play->kind() == JointPlay::kind_name);
  REQUIRE(play->terms().size() == 1);
  CHECK(play->terms()[0].label == "20 H11/d11");
  CHECK(play->joint() == "pin in 1 bore (20 H11/d11)");
}

TEST_CASE("joint.pin: two fits (clevis) add in series", "[joints][pin]") {
  const OutputSet out = run_pin({H11_d11, H11_h11});
  CHECK_THAT(scalar(out, "play_min"), WithinRel((65 + 0) * um, 1e-12));
  CHECK_THAT(scalar(out, "play_max"), WithinRel((325 + 260) * um, 1e-12));
  CHECK_THAT(scalar(out, "play_mean"), WithinRel((195 + 130) * um, 1e-12));
  CHECK(play_of(out)->terms().size() == 2);
  CHECK(play_of(out)->joint() == "pin in 2 bores (20 H11/d11, 20 H11/h11)");
}

TEST_CASE("joint.pin: an interference fit gives no play, a transition fit only its positive part", "[joints][pin]") {
  const OutputSet press = run_pin({H7_s6});
  CHECK(scalar(press, "play_min") == 0.0);
  CHECK(scalar(press, "play_max") == 0.0);
  CHECK(scalar(press, "play_mean") == 0.0);

  // A pin pressed into the clevis and running in the rod eye: only the running fit plays.
  const OutputSet mixed = run_pin({H11_d11, H7_s6});
  CHECK_THAT(scalar(mixed, "play_min"), WithinRel(65 * um, 1e-12));
  CHECK_THAT(scalar(mixed, "play_max"), WithinRel(325 * um, 1e-12));
  CHECK_THAT(scalar(mixed, "play_mean"), WithinRel(195 * um, 1e-12));

  const OutputSet k6 = run_pin({H7_k6});
  CHECK(scalar(k6, "play_min") == 0.0);
  CHECK_THAT(scalar(k6, "play_max"), WithinRel(19 * um, 1e-12));
  CHECK_THAT(scalar(k6, "play_mean"), WithinRel(2 * um, 1e-10));

  // mean -11 um is clipped to 0 for play_mean, the upper limit +6 um still counts for play_max
  const OutputSet n6 = run_pin({H7_n6});
  CHECK(scalar(n6, "play_min") == 0.0);
  CHECK_THAT(scalar(n6, "play_max"), WithinRel(6 * um, 1e-10));
  CHECK(scalar(n6, "play_mean") == 0.0);
  CHECK_THAT(play_of(n6)->terms()[0].mean(), WithinAbs(-11 * um, 1e-15));  // the term itself stays untruncated
}

TEST_CASE("joint.pin: play_factor projects the clearance, label names the joint", "[joints][pin]") {
  const OutputSet out = run_pin({H11_d11, H11_h11}, {{"play_factor", ParamValue::of_number(0.5)}, {"label", ParamValue::of_text("hinge 1")}});
  CHECK_THAT(scalar(out, "play_min"), WithinRel(0.5 * 65 * um, 1e-12));
  CHECK_THAT(scalar(out, "play_max"), WithinRel(0.5 * 585 * um, 1e-12));
  CHECK_THAT(scalar(out, "play_mean"), WithinRel(0.5 * 325 * um, 1e-12));
  CHECK(play_of(out)->joint() == "hinge 1");
  CHECK(play_of(out)->terms()[0].links[1].sensitivity == -0.5);  // the shaft link
}

TEST_CASE("joint.pin: no fit is an error naming fits", "[joints][pin]") {
  CHECK_THROWS_MATCHES(run_pin({}), NodeError, Catch::Matchers::Predicate<NodeError>([](const NodeError& e) {
                         return e.parameter() == "fits" && std::string(e.what()).find("at least one fit") != std::string::npos;
                       }));
}
