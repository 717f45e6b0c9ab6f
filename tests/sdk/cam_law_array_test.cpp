// Cam laws over arrays of cases (mechgraph/domain/cam_law_array.hpp): a lane answers everything
// from its array, the host's contract check sees a lane as any law, and lanes_of finds the array
// only when every case that holds a law holds its own lane of one array.
#include <catch2/catch.hpp>

#include <mechgraph/domain/cam_law_array.hpp>
#include <mechgraph/domain/cam_law_block.hpp>

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

using namespace mechgraph;

namespace {

// A family for the test: the cosine bump h = L (1 + cos(pi phi / p)) / 2 on (-p, p), lane k of
// lift L_k and half event p_k, a breakpoint at the nose (jerk's sign flips there only in this
// test's telling), closed-form integrals of h; and a lane that answers NaN where asked to.
class BumpArray final : public CamLawArray {
 public:
  BumpArray(std::vector<double> lift, std::vector<double> half, double nan_lane = -1)
      : lift_(std::move(lift)), half_(std::move(half)), nan_lane_(nan_lane) {
    for (std::size_t k = 0; k < lift_.size(); ++k) {
      at_.emplace_back(this, k);
      begin_.push_back(-half_[k]);
      base_.push_back(0.02);
      roller_.push_back(0.005 * static_cast<double>(k));
    }
  }
  std::size_t lanes() const override { return lift_.size(); }
  CamLawColumns columns() const override { return {begin_.data(), half_.data(), lift_.data(), base_.data(), roller_.data()}; }
  void evaluate(const std::uint32_t* lane, const double* phi, std::size_t n, LiftDerivatives* out) const override {
    for (std::size_t i = 0; i < n; ++i) out[i] = evaluate_one(lane ? lane[i] : i, phi[i]);
  }
  Point point(std::size_t lane) const override {
    return {[](const void* data, double phi) {
              const auto* at = static_cast<const std::pair<const BumpArray*, std::size_t>*>(data);
              return at->first->evaluate_one(at->second, phi);
            },
            &at_[lane]};
  }
  LiftDerivatives evaluate_one(std::size_t lane, double phi) const {
    if (static_cast<double>(lane) == nan_lane_) return {std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0, 0.0};
    const double L = lift_[lane], w = std::numbers::pi / half_[lane], c = std::cos(w * phi), s = std::sin(w * phi);
    return {0.5 * L * (1.0 + c), -0.5 * L * w * s, -0.5 * L * w * w * c, 0.5 * L * w * w * w * s};
  }
  std::span<const double> breakpoints(std::size_t) const override { return {&nose_, 1}; }
  bool higher_derivatives(std::size_t lane, double phi, double& d4, double& d5) const override {
    const double L = lift_[lane], w = std::numbers::pi / half_[lane];
    d4 = 0.5 * L * std::pow(w, 4) * std::cos(w * phi);
    d5 = -0.5 * L * std::pow(w, 5) * std::sin(w * phi);
    return true;
  }
  bool monotone_breaks(std::size_t, int order, std::vector<double>& breaks) const override {
    if (order != 0) return false;
    breaks = {0.0};
    return true;
  }
  bool lift_integrals(std::size_t lane, double a, double b, double& integral, double& integral_of_square) const override {
    const double L = lift_[lane], w = std::numbers::pi / half_[lane];
    integral = 0.5 * L * ((b - a) + (std::sin(w * b) - std::sin(w * a)) / w);
    integral_of_square = -1.0;  // not checked here
    return lane == 0;
  }

 private:
  std::vector<double> lift_, half_, begin_, base_, roller_;
  std::vector<std::pair<const BumpArray*, std::size_t>> at_;  // each lane's data: the array and the lane
  double nan_lane_;
  double nose_ = 0.0;
};

// A law of its own (no array): lift L (1 - (phi/p)^2)^2 on (-1, 1), L = 1 cm.
class PlainLaw final : public CamLaw {
 public:
  double event_begin() const override { return -1.0; }
  double event_end() const override { return 1.0; }
  LiftDerivatives evaluate_in_event(double phi) const override {
    const double m = 1.0 - phi * phi;
    return {1e-2 * m * m, -4e-2 * phi * m, 1e-2 * (12.0 * phi * phi - 4.0), 24e-2 * phi};
  }
  std::vector<double> breakpoints() const override { return {}; }
  double max_lift() const override { return 1e-2; }
  double base_radius() const override { return 2e-2; }
};

std::shared_ptr<const CamLawArray> bumps(double nan_lane = -1) {
  return std::make_shared<const BumpArray>(std::vector<double>{8e-3, 9e-3, 10e-3}, std::vector<double>{1.0, 1.1, 1.2}, nan_lane);
}

}  // namespace

TEST_CASE("cam law arrays: a lane answers every question from its array", "[sdk][cam_law_array]") {
  const auto array = bumps();
  const CamLawLane lane(array, 1);
  CHECK(&lane.array() == array.get());
  CHECK(lane.lane() == 1);
  CHECK(lane.event_begin() == -1.1);
  CHECK(lane.event_end() == 1.1);
  CHECK(lane.max_lift() == 9e-3);
  CHECK(lane.base_radius() == 0.02);
  CHECK(lane.roller_radius() == 0.005);
  CHECK(lane.breakpoints() == std::vector<double>{0.0});
  for (double phi : {-1.0, -0.3, 0.0, 0.7}) {
    const std::uint32_t one = 1;
    LiftDerivatives b;
    array->evaluate(&one, &phi, 1, &b);
    const LiftDerivatives a = lane.evaluate_in_event(phi);
    CHECK(a.lift == b.lift);
    CHECK(a.velocity == b.velocity);
    CHECK(a.acceleration == b.acceleration);
    CHECK(a.jerk == b.jerk);
  }
  // The lift at the nose is the lane's max lift; at a quarter of the event, half of it.
  CHECK_THAT(lane.evaluate_in_event(0.0).lift, Catch::Matchers::WithinRel(9e-3, 1e-15) || Catch::Matchers::WithinAbs(9e-3, 1e-18));
  CHECK_THAT(lane.evaluate_in_event(0.55).lift, Catch::Matchers::WithinRel(4.5e-3, 1e-14) || Catch::Matchers::WithinAbs(4.5e-3, 1e-18));
  double d4 = 0.0, d5 = 0.0;
  CHECK(lane.higher_derivatives(0.0, d4, d5));
  CHECK_THAT(d4, Catch::Matchers::WithinRel(0.5 * 9e-3 * std::pow(std::numbers::pi / 1.1, 4), 1e-14));
  std::vector<double> runs;
  CHECK(lane.monotone_breaks(0, runs));
  CHECK(runs == std::vector<double>{0.0});
  CHECK_FALSE(lane.monotone_breaks(1, runs));
  double integral = 0.0, square = 0.0;
  CHECK_FALSE(lane.lift_integrals(-1.1, 1.1, integral, square));  // lane 1 has no closed form here
  const CamLawLane first(array, 0);
  REQUIRE(first.lift_integrals(-1.0, 1.0, integral, square));
  CHECK_THAT(integral, Catch::Matchers::WithinRel(8e-3, 1e-14) || Catch::Matchers::WithinAbs(8e-3, 1e-18));  // L p
  // A lane is checked as any law: the contract holds for these, and a NaN of its array is refused.
  CHECK(lane.contract_problem().empty());
  CHECK_THAT(CamLawLane(bumps(2), 2).contract_problem(), Catch::Matchers::Contains("NaN"));
  CHECK(CamLawLane(bumps(2), 1).contract_problem().empty());
}

TEST_CASE("cam law arrays: a lane past the array or of no array is refused", "[sdk][cam_law_array]") {
  CHECK_THROWS_AS(CamLawLane(bumps(), 3), std::out_of_range);
  CHECK_THROWS_AS(CamLawLane(nullptr, 0), std::invalid_argument);
}

TEST_CASE("cam law arrays: lanes_of finds the array only when case k holds lane k of it", "[sdk][cam_law_array]") {
  const auto array = bumps();
  const auto other = bumps();
  auto lane = [](const std::shared_ptr<const CamLawArray>& of, std::size_t k) -> std::shared_ptr<const CamLaw> {
    return std::make_shared<const CamLawLane>(of, k);
  };
  using Laws = std::vector<std::shared_ptr<const CamLaw>>;
  CHECK(lanes_of(CamLawBlock(Laws{lane(array, 0), lane(array, 1), lane(array, 2)})) == array.get());
  // A failed case holds no law: the others still make the array.
  CHECK(lanes_of(CamLawBlock(Laws{lane(array, 0), nullptr, lane(array, 2)})) == array.get());
  // Lanes out of their cases, of two arrays, or beside a plain law: no array.
  CHECK(lanes_of(CamLawBlock(Laws{lane(array, 1), lane(array, 0)})) == nullptr);
  CHECK(lanes_of(CamLawBlock(Laws{lane(array, 0), lane(other, 1)})) == nullptr);
  const std::shared_ptr<const CamLaw> plain = std::make_shared<const PlainLaw>();
  CHECK(plain->contract_problem().empty());
  CHECK(lanes_of(CamLawBlock(Laws{lane(array, 0), plain})) == nullptr);
  CHECK(lanes_of(CamLawBlock(Laws{plain, lane(array, 1)})) == nullptr);
  // No case computed: nothing to evaluate, no array.
  CHECK(lanes_of(CamLawBlock(Laws{nullptr, nullptr})) == nullptr);
  // One law for every case: lane 0 of its array, and the array answers for case 0 only.
  CHECK(lanes_of(CamLawBlock(Laws{lane(array, 0)})) == array.get());
  CHECK(lanes_of(CamLawBlock(Laws{lane(array, 1)})) == nullptr);
}
