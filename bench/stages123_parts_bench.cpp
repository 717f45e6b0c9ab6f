// Where a stage 1-3 case's time goes, part by part: the baseline the batch path is measured against
// (docs/design/sdk-1.6-laws-over-arrays.md, section 1 and step 0; docs/peers.md quotes it).
//   build/bench/mechgraph_bench --benchmark_filter=Stages123Part
// Each part runs on the three laws of every case of 1,000 designs drawn over the peers' box
// (lift 7-9 mm, action 120-140 deg, accel angle 15-21 deg, base radius 24-28 mm, lash 0.1-0.4 mm;
// rocker ratio 1.5; the polydyne's exponents 2, 14, 26, 38, 50), by the functions the block path
// calls, in the order it calls them:
//   make       the three laws from the case's numbers (cam.three_arc, cam.kurz, cam.polydyne)
//   contract   CamLaw::contract_problem() of each: the host's check of every law a node returns
//   open       find_open_period: the valve's opening and closing (the lash crossings)
//   peaks      find_valve_peaks: the acceleration's extremes over the open period (the peers' scene
//              reads no valve velocity, so its block path leaves the velocity's runs unread)
//   integrals  CamLaw::lift_integrals over the open period: the time-area's closed form
// The time and the law's evaluations (none for make) are per case (three designs). A case of the
// peers' sweep (bench/peers/stages123_study.yaml) is these parts and the evaluator's block plan,
// the parameters and the rows; BM_SweepStages123 asks for more outputs (the cams' summaries, the
// valve's velocity), whose searches are not among these parts.
#include <mechgraph/domain/cam_law.hpp>

#include "kurz.hpp"
#include "polydyne.hpp"
#include "three_arc.hpp"
#include "valve_motion.hpp"

#include <benchmark/benchmark.h>

#include <array>
#include <memory>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

namespace {

using namespace mechgraph;

constexpr double degree = std::numbers::pi / 180.0;
constexpr double rocker_ratio = 1.5;
constexpr int samples = 16;  // valvetrain.valve_motion's default (unused where a law declares its runs)

struct Design {
  cams::CamBasics basics;
  double accel_angle = 0.0, lash = 0.0;
};

// The designs: uniform over the box from a fixed seed, the same on every run.
const std::vector<Design>& designs() {
  static const std::vector<Design> all = [] {
    std::mt19937_64 random(20261201);
    auto within = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(random); };
    std::vector<Design> out(1000);
    for (Design& d : out) {
      d.basics.max_lift = within(7e-3, 9e-3);
      d.basics.action_angle = within(120.0, 140.0) * degree;
      d.accel_angle = within(15.0, 21.0) * degree;
      d.basics.base_radius = within(24e-3, 28e-3);
      d.lash = within(0.1e-3, 0.4e-3);
    }
    return out;
  }();
  return all;
}

using CaseLaws = std::array<std::shared_ptr<const CamLaw>, 3>;

CaseLaws make_laws(const Design& d) {
  return {std::make_shared<const cams::ThreeArcLaw>(cams::three_arc_from_accel_angle(d.basics, d.accel_angle), 0.0),
          cams::make_kurz_law(d.basics, d.accel_angle, std::nullopt),
          std::make_shared<const cams::PolydyneLaw>(d.basics.max_lift, d.basics.action_angle, d.basics.base_radius,
                                                    std::vector<int>{2, 14, 26, 38, 50})};
}

const std::vector<CaseLaws>& laws() {
  static const std::vector<CaseLaws> all = [] {
    std::vector<CaseLaws> out;
    for (const Design& d : designs()) out.push_back(make_laws(d));
    return out;
  }();
  return all;
}

const std::vector<std::array<valvetrain::OpenPeriod, 3>>& open_periods() {
  static const std::vector<std::array<valvetrain::OpenPeriod, 3>> all = [] {
    std::vector<std::array<valvetrain::OpenPeriod, 3>> out(designs().size());
    long evaluations = 0;
    for (std::size_t k = 0; k < out.size(); ++k)
      for (std::size_t c = 0; c < 3; ++c)
        out[k][c] = valvetrain::find_open_period(*laws()[k][c], rocker_ratio, designs()[k].lash, samples, evaluations);
    return out;
  }();
  return all;
}

enum Part { make, contract, open, peaks, integrals };
const char* const part_names[] = {"make", "contract", "open", "peaks", "integrals"};

void BM_Stages123Part(benchmark::State& state) {
  const auto part = static_cast<Part>(state.range(0));
  const std::vector<Design>& cases = designs();
  const std::vector<CaseLaws>& made = laws();
  const auto& opened = open_periods();
  valvetrain::ValveSearchScratch scratch;  // reused from case to case, as the block path does
  long evaluations = 0;
  for (auto _ : state) {
    for (std::size_t k = 0; k < cases.size(); ++k) {
      switch (part) {
        case make:
          benchmark::DoNotOptimize(make_laws(cases[k]));
          break;
        case contract:
          for (const auto& law : made[k])
            if (!law->contract_problem().empty()) throw std::logic_error("a law of the bench's box breaks its contract");
          break;
        case open:
          for (const auto& law : made[k])
            benchmark::DoNotOptimize(
                valvetrain::find_open_period(*law, rocker_ratio, cases[k].lash, samples, evaluations, scratch));
          break;
        case peaks:
          for (std::size_t c = 0; c < 3; ++c)
            benchmark::DoNotOptimize(valvetrain::find_valve_peaks(*made[k][c], opened[k][c], rocker_ratio, cases[k].lash,
                                                                  samples, evaluations, scratch, false));
          break;
        case integrals:
          for (std::size_t c = 0; c < 3; ++c) {
            double integral = 0.0, of_square = 0.0;
            if (!made[k][c]->lift_integrals(opened[k][c].begin, opened[k][c].end, integral, of_square))
              throw std::logic_error("a law of the bench's box gives no lift integrals");
            benchmark::DoNotOptimize(integral + of_square);
            evaluations += 2;
          }
          break;
      }
    }
  }
  const double cases_run = static_cast<double>(state.iterations()) * static_cast<double>(cases.size());
  state.SetItemsProcessed(static_cast<std::int64_t>(cases_run));
  state.counters["s/case"] = benchmark::Counter(cases_run, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  if (part == contract) {  // its sample points: 16 across the event and the middle of each piece, per law
    evaluations = 0;
    for (const CaseLaws& three : made)
      for (const auto& law : three) evaluations += 16 + static_cast<long>(law->breakpoints().size()) + 1;
    evaluations *= state.iterations();
  }
  state.counters["evaluations/case"] = static_cast<double>(evaluations) / cases_run;
  state.SetLabel(part_names[part]);
}
BENCHMARK(BM_Stages123Part)->DenseRange(make, integrals)->Unit(benchmark::kMicrosecond);

}  // namespace
