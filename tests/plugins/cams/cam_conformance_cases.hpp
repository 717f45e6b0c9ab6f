#pragma once
// The cam conformance suite's table: one entry per cam node type (a type without an entry fails the
// suite), the design scenarios every type is run through, and the small harness that evaluates a
// cam node the way the host would (parameters parsed from scene-like text, defaults filled in,
// ranges checked). See cam_conformance_test.cpp for the checks.
#include "cam_node.hpp"
#include "ramps.hpp"
#include "rise_law.hpp"
#include "test_support.hpp"

#include <mechgraph/node.hpp>
#include <mechgraph/units.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <string>
#include <vector>

#include <unistd.h>

namespace mechgraph::cams::testing {

inline constexpr double deg = std::numbers::pi / 180.0;
inline constexpr double mm = 1e-3;

/// A host stand-in: no effects, logs kept, work counted.
using TestContext = mechgraph::testing::RecordingContext;

/// An SI value as scene text ("0.0090000000000000002 m"), parsed back exactly.
inline std::string si(double value, const char* unit) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g %s", value, unit);
  return buffer;
}

/// Parameters as the scene would give them (text), turned into a ParamSet the way the host does
/// (the SDK kit's harness: units, dimension, choices and the host's range check; defaults filled in,
/// examples not, since the cases state every design value). A mistake in the test setup throws
/// std::invalid_argument (not NodeError).
inline ParamSet make_params(const NodeInfo& info, const std::map<std::string, std::string>& values) {
  return mechgraph::testing::params_with_defaults(info, values, /*fill_examples=*/false);
}

/// A file the test writes into the temporary folder, removed when the object goes.
class TempFile {
 public:
  TempFile(const std::string& name, const std::string& content)
      : path_((std::filesystem::temp_directory_path() /
               ("mechgraph_cams_test_" + std::to_string(::getpid()) + "_" + name))
                  .string()) {
    std::ofstream(path_) << content;
  }
  ~TempFile() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// The result of evaluating one cam node.
struct Evaluation {
  std::shared_ptr<const CamLaw> law;
  OutputSet outputs;
  TestContext context;
};

inline Evaluation evaluate_node(const NodeType& type, const std::map<std::string, std::string>& values,
                                const InputSet& inputs = {}) {
  Evaluation e;
  type.evaluate(make_params(type.info(), values), inputs, e.outputs, e.context);
  const auto& all = e.outputs.all();
  const auto it = all.find("law");
  if (it == all.end()) throw std::logic_error(type.info().type + " did not set its 'law' output");
  e.law = std::dynamic_pointer_cast<const CamLaw>(it->second.as_handle());
  if (!e.law) throw std::logic_error(type.info().type + ": output 'law' is not a CamLaw");
  return e;
}

inline const NodeType* find_type(const NodeTypeList& types, std::string_view name) {
  for (const auto& t : types)
    if (t->info().type == name) return t.get();
  return nullptr;
}

/// The common design values of one run.
struct Scenario {
  std::string name;
  double max_lift = 9.0 * mm;
  double action_angle = 130.0 * deg;
  double base_radius = 60.0 * mm;
  RampSpec ramp{};
  /// Every law must refuse this design with a NodeError (naming `expected_parameter` if set).
  bool must_fail = false;
  std::string expected_parameter;
};

/// The common parameters of a scenario as scene text.
inline std::map<std::string, std::string> common_params(const Scenario& s) {
  std::map<std::string, std::string> p{{"max_lift", si(s.max_lift, "m")},
                                       {"action_angle", si(s.action_angle, "rad")},
                                       {"base_radius", si(s.base_radius, "m")},
                                       // the events are measured at a lift every scenario reaches
                                       {"checking_lift", si(0.1 * s.max_lift, "m")}};
  if (s.ramp.type != RampType::none) {
    p["ramp"] = std::string(ramp_type_name(s.ramp.type));
    p["ramp_height"] = si(s.ramp.height, "m");
    p["ramp_length"] = si(s.ramp.length, "rad");
  }
  return p;
}

/// The main law's lift in a scenario: max_lift less the ramp's share (see ramps.hpp).
inline double main_lift(const Scenario& s) { return s.max_lift - ramp_lift_at_nose(s.ramp, 0.5 * s.action_angle); }

/// The design scenarios. Nominal values are a passenger-car valve cam with a base circle large
/// enough for the undercut-prone textbook laws (cycloidal, 4-5-6-7 need r0 > 45 mm at 9 mm/130 deg).
inline const std::vector<Scenario>& conformance_scenarios() {
  static const std::vector<Scenario> scenarios = [] {
    auto make = [](std::string name, double lift, double angle, double r0) {
      Scenario s;
      s.name = std::move(name);
      s.max_lift = lift;
      s.action_angle = angle;
      s.base_radius = r0;
      return s;
    };
    std::vector<Scenario> v;
    const Scenario nominal = make("nominal", 9.0 * mm, 130.0 * deg, 60.0 * mm);
    v.push_back(nominal);
    Scenario cv = nominal;
    cv.name = "constant_velocity_ramp";
    cv.ramp = {RampType::constant_velocity, 0.3 * mm, 20.0 * deg};
    v.push_back(cv);
    Scenario cosine = nominal;
    cosine.name = "cosine_ramp";
    cosine.ramp = {RampType::cosine, 0.3 * mm, 20.0 * deg};
    v.push_back(cosine);
    v.push_back(make("tiny_lift_1um", 1e-6, 130.0 * deg, 60.0 * mm));
    v.push_back(make("huge_lift_1m", 1.0, 130.0 * deg, 10.0));
    v.push_back(make("tiny_angle_0.5deg", 1e-6, 0.5 * deg, 1.0));
    v.push_back(make("huge_angle_350deg", 9.0 * mm, 350.0 * deg, 17.0 * mm));
    Scenario ramp_too_high = nominal;
    ramp_too_high.name = "ramp_taller_than_lift";
    ramp_too_high.ramp = {RampType::constant_velocity, 9.0 * mm, 20.0 * deg};
    ramp_too_high.must_fail = true;
    ramp_too_high.expected_parameter = "ramp_height";
    v.push_back(ramp_too_high);
    return v;
  }();
  return scenarios;
}

/// One entry per cam node type.
struct ConformanceCase {
  std::string type;
  /// The law-specific parameters (scene text) for a scenario.
  std::function<std::map<std::string, std::string>(const Scenario&)> params = [](const Scenario&) {
    return std::map<std::string, std::string>{};
  };
  /// Highest derivative continuous everywhere, ramps off (0 lift only, 1 velocity, 2 acceleration,
  /// 3 jerk). With a cosine ramp the suite expects min(continuity, 1), with a constant-velocity
  /// ramp 0.
  int continuity = 0;
  /// Relative tolerance of the maximum lift over the event against max_lift.
  double lift_tolerance = 1e-9;
  bool symmetric = true;
  bool peak_at_nose = true;
  /// Scenarios this law may refuse with a NodeError (a clear error, never NaN).
  std::set<std::string> may_fail;
  /// Inputs, for laws with input ports.
  std::function<void(const Scenario&, InputSet&)> inputs;
};

/// A CSV of the 4-5-6-7 rise-return (lift net of the ramp) over the scenario's action angle:
/// cam.table's sample data. The suite removes the file after the scenario (see scenario_files).
inline std::string write_sample_table(const Scenario& s) {
  const double H = std::max(main_lift(s), 1e-3 * s.max_lift);
  const SymmetricRiseReturnLaw law(RiseShape::poly4567, H, s.action_angle, 1.0);
  const auto path = std::filesystem::temp_directory_path() /
                    ("mechgraph_cam_conformance_" + std::to_string(::getpid()) + "_" + s.name + ".csv");
  std::ofstream out(path);
  out << "# 4-5-6-7 rise-return, " << H * 1e3 << " mm over " << s.action_angle / deg << " deg\n";
  out << "angle_deg, lift_mm\n";
  const int rows = 241;
  char line[96];
  for (int i = 0; i < rows; ++i) {
    const double phi = (i == rows - 1) ? law.event_end() : law.event_begin() + s.action_angle * i / (rows - 1);
    const double lift = (i == 0 || i == rows - 1) ? 0.0 : law.at(phi).lift;
    std::snprintf(line, sizeof line, "%.17g, %.17g\n", phi / deg, lift / mm);
    out << line;
  }
  return path.string();
}

/// Whether a parameter value is a file the suite wrote for one scenario (to be removed after it).
inline bool is_scenario_file(const std::string& value) {
  const std::string prefix = (std::filesystem::temp_directory_path() / "mechgraph_cam_conformance_").string();
  return value.rfind(prefix, 0) == 0;
}

/// The table. A node type found in add_source_profile_types or add_standard_law_types without an
/// entry here fails the suite.
inline const std::vector<ConformanceCase>& conformance_cases() {
  static const std::vector<ConformanceCase> cases = [] {
    std::vector<ConformanceCase> v;
    for (RiseShape shape : all_rise_shapes) {
      ConformanceCase c;
      c.type = "cam." + std::string(rise_shape_name(shape));
      c.continuity = rise_return_continuity(shape);
      v.push_back(c);
    }
    {
      ConformanceCase c;
      c.type = "cam.table";
      c.params = [](const Scenario& s) {
        return std::map<std::string, std::string>{{"file", write_sample_table(s)}};
      };
      c.continuity = 0;  // the data decide: a table may start with a velocity step
      c.lift_tolerance = 1e-3;
      v.push_back(c);
    }
    // The source study's profiles (docs/methods/valvetrain.md). Their accel_angle keeps the
    // proportion of the scene example (18 deg of 130 deg). Continuity: three-arc, acceleration
    // steps at the start and at the flank/nose junction; Kurz and polydyne, shockless (jerk may
    // step).
    const std::set<std::string> hard{"tiny_lift_1um", "huge_lift_1m", "tiny_angle_0.5deg", "huge_angle_350deg"};
    auto accel_angle = [](const Scenario& s) {
      return std::map<std::string, std::string>{{"accel_angle", si(s.action_angle * 18.0 / 130.0, "rad")}};
    };
    {
      ConformanceCase c;
      c.type = "cam.three_arc";
      c.params = accel_angle;
      c.continuity = 1;
      c.may_fail = hard;
      v.push_back(c);
    }
    {
      ConformanceCase c;
      c.type = "cam.kurz";
      c.params = accel_angle;
      c.continuity = 2;
      c.may_fail = hard;
      v.push_back(c);
    }
    {
      ConformanceCase c;
      c.type = "cam.polydyne";
      c.continuity = 2;
      c.may_fail = hard;
      v.push_back(c);
    }
    return v;
  }();
  return cases;
}

inline const ConformanceCase* find_case(std::string_view type) {
  for (const auto& c : conformance_cases())
    if (c.type == type) return &c;
  return nullptr;
}

}  // namespace mechgraph::cams::testing
