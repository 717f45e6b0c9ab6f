#include "cam_node.hpp"

#include <mechgraph/block.hpp>
#include <mechgraph/domain/cam_law_block.hpp>

#include <mechgraph/domain/cam_curves.hpp>
#include <mechgraph/domain/cam_geometry.hpp>
#include "ramps.hpp"

#include <mechgraph/numerics/piecewise.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>
#include <vector>

namespace mechgraph::cams {
namespace {

constexpr double pi = std::numbers::pi;

// The cost of the searches over a law, per smooth piece (measured by the calibration test,
// tests/core/work_estimate_calibration_test.cpp): the summary and the events interpolate each
// piece at 33 points or more, for a few functions, and keep the interpolants while they search.
constexpr double summary_items_per_piece = 400.0;
constexpr double summary_bytes_per_piece = 8192.0;
// An svaj row: angle, lift and three derivatives (and crank angle), kept as the table.
constexpr double svaj_bytes_per_point = 64.0;

// The common ramp parameters, checked: `ramp: none` with a height or length set is an error
// rather than silently ignored; a ramp needs both.
RampSpec read_ramp(const ParamSet& params) {
  RampSpec r;
  const std::string name = params.has("ramp") ? params.text("ramp") : std::string("none");
  const auto type = ramp_type_from_name(name);
  if (!type) throw NodeError("ramp", "unknown ramp '" + name + "'; valid ramps are: none constant_velocity cosine");
  r.type = *type;
  r.height = params.has("ramp_height") ? params.number("ramp_height") : 0.0;
  r.length = params.has("ramp_length") ? params.number("ramp_length") : 0.0;
  // The stream is made only for a refusal: every evaluation reads the ramp, few are refused.
  if (!(std::isfinite(r.height) && r.height >= 0.0)) {
    std::ostringstream m;
    m << "ramp_height must be >= 0 (got " << r.height * 1e3 << " mm)";
    throw NodeError("ramp_height", m.str());
  }
  if (!(std::isfinite(r.length) && r.length >= 0.0)) {
    std::ostringstream m;
    m << "ramp_length must be >= 0 (got " << r.length * 180.0 / pi << " deg)";
    throw NodeError("ramp_length", m.str());
  }
  if (r.type == RampType::none) {
    if (r.height != 0.0) {
      std::ostringstream m;
      m << "ramp_height is " << r.height * 1e3 << " mm but ramp is none; choose ramp: constant_velocity or cosine";
      throw NodeError("ramp_height", m.str());
    }
    if (r.length != 0.0) {
      std::ostringstream m;
      m << "ramp_length is " << r.length * 180.0 / pi << " deg but ramp is none; choose ramp: constant_velocity or cosine";
      throw NodeError("ramp_length", m.str());
    }
    return r;
  }
  if (!(r.height > 0.0)) throw NodeError("ramp_height", "ramp " + name + " needs ramp_height > 0");
  if (!(r.length > 0.0)) throw NodeError("ramp_length", "ramp " + name + " needs ramp_length > 0");
  return r;
}

// The main law's share of max_lift once the ramp has taken its own (see ramps.hpp).
double main_lift(const RampSpec& ramp, double max_lift, double action_angle) {
  if (ramp.type == RampType::none) return max_lift;
  if (!(action_angle + 2.0 * ramp.length < 2.0 * pi)) {
    std::ostringstream m;
    m << "action_angle + 2 ramp_length = " << (action_angle + 2.0 * ramp.length) * 180.0 / pi
      << " deg must stay below 360 deg";
    throw NodeError("ramp_length", m.str());
  }
  const double share = ramp_lift_at_nose(ramp, 0.5 * action_angle);
  if (!(share < max_lift)) {
    std::ostringstream m;
    m << "the " << ramp_type_name(ramp.type) << " ramp takes " << share * 1e3 << " mm of the lift at the nose (ramp_height "
      << ramp.height * 1e3 << " mm + its end velocity " << ramp_end_velocity(ramp) * 1e3 * pi / 180.0
      << " mm/deg faded out over half the action angle), not less than max_lift " << max_lift * 1e3
      << " mm; lower ramp_height or lengthen ramp_length";
    throw NodeError("ramp_height", m.str());
  }
  return max_lift - share;
}

class CamNodeType final : public NodeType, public BlockEvaluation, public ForecastReads {
 public:
  explicit CamNodeType(CamLawDefinition d)
      : make_(std::move(d.make)), cost_(std::move(d.cost)), prepare_block_(std::move(d.prepare_block)),
        derived_(d.derives_lift_and_action) {
    // What forecast() reads: the ramp, samples and curve_points, and what the law's cost reads. A
    // cost that does not say may read any parameter: then the type says nothing.
    if (!cost_ || d.cost_reads) {
      reads_ = std::vector<std::string>{"ramp", "samples", "curve_points"};
      if (d.cost_reads) reads_->insert(reads_->end(), d.cost_reads->begin(), d.cost_reads->end());
    }
    const std::string derived_from = d.derived_from;
    info_.type = std::move(d.type);
    info_.version = d.version;
    info_.summary = std::move(d.summary);
    // Every declaration is moved into info_ (a node type is built at every process start): the
    // fluent setters return a reference, which a braced list or a push_back would copy.
    const auto param = [this](ParamSpec& p) { info_.params.push_back(std::move(p)); };
    param(ParamSpec::number("max_lift", dim::length,
                            "maximum follower lift at the nose; with a ramp the total lift: the ramp's share "
                            "(ramp_height + its end velocity faded out by the nose, see ramp) plus the main law's",
                            "mm")
              .positive()
              .at_most(1e3)
              .because("> 0: a lift event must lift; <= 1 km: squares of a lift (time-area, energies) stay far inside a double")
              .with_example(9e-3));
    param(ParamSpec::number("action_angle", dim::angle,
                            "total cam angle of the lift event of the main law (ramps add 2 ramp_length); from 0.1 deg, "
                            "below which the derivatives (h / phi^2, h / phi^3) leave the range of a double for any lift",
                            "deg")
              .at_least(min_action_angle)
              .below(2.0 * std::numbers::pi)
              .because(">= 0.1 deg: below it h / phi^2 and h / phi^3 leave the range of a double for some lift; < 360 deg: the event fits in one turn")
              .with_example(130.0 * std::numbers::pi / 180.0));
    param(ParamSpec::number("base_radius", dim::length, "base-circle radius", "mm").positive().because("> 0: a radius").with_example(60e-3));
    if (derived_) {
      for (std::size_t i = 0; i < 2; ++i) {
        info_.params[i].optional();
        info_.params[i].doc += " (taken from " + derived_from + "; give it only to check " + derived_from + " against it)";
      }
    }
    for (auto& p : d.params) info_.params.push_back(std::move(p));
    param(ParamSpec::choice("ramp", ramp_type_names(),
                            "opening/closing ramps taking up the lash, superposed on the law: none; "
                            "constant_velocity (lift grows linearly to ramp_height over ramp_length: the velocity "
                            "jumps at the start of the ramp, an acceleration impulse, not shockless); cosine "
                            "(ramp_height (1 - cos(pi x/2)): velocity continuous, finite acceleration step at the start). "
                            "The ramp's end velocity is carried into the main lift and faded to zero at the nose by a "
                            "3-4-5 polynomial, so lift, velocity (and for cosine acceleration) are continuous at the "
                            "ramp/main junction; the event grows to action_angle + 2 ramp_length, symmetric")
              .with_default("none"));
    param(ParamSpec::number("ramp_height", dim::length, "lift at the end of each ramp (set with a ramp, 0 without)", "mm")
              .with_default(0.0)
              .non_negative()
              .because(">= 0: a lift (0: no ramp)"));
    param(ParamSpec::number("ramp_length", dim::angle,
                            "cam angle of each ramp, before and after the action angle (set with a ramp, 0 without)",
                            "deg")
              .with_default(0.0)
              .non_negative()
              .below(pi - 0.5 * min_action_angle)
              .because(">= 0: an angle (0: no ramp); < 180 - 0.05 deg: action_angle (at least 0.1 deg) plus two ramps must stay below 360 deg"));
    param(ParamSpec::integer("samples", "samples per smooth piece for the extremum searches (each extremum then refined to full precision, by the root of its derivative or Brent; 16 agree with 3200 to 1e-13 on every example cam and 8 already do, mechgraph bench shows it)")
              .with_default(16.0)
              .at_least(8)
              .at_most(1e6)
              .because(">= 8: fewer cannot certify a piece's interpolant; <= 1e6: 8 already agree with 3200 to 1e-13, more only costs time")
              .as_knob());
    info_.params.push_back(checking_lift_param("cam"));
    info_.params.push_back(nose_timing_param());
    param(ParamSpec::integer("curve_points", "points of the svaj table, evenly spaced over the event "
                                             "widened by a tenth of its width each side")
              .with_default(361.0)
              .at_least(3)
              .at_most(1e6)
              .because(">= 3: a curve needs its two ends and a point between; <= 1e6: a table for plotting, bounded in memory"));
    info_.outputs.push_back(PortSpec::handle("law", std::string(CamLaw::kind_name), "follower lift over cam angle with 3 derivatives"));
    info_.outputs.push_back(PortSpec::scalar("max_lift", dim::length, "follower (tappet) lift at the nose, ramps included", "mm"));
    info_.outputs.push_back(PortSpec::scalar("max_velocity", dim::length / dim::angle, "max |dh/dphi|", "mm/deg"));
    info_.outputs.push_back(PortSpec::scalar("max_acceleration", dim::length / dim::angle.pow(2), "max d2h/dphi2"));
    info_.outputs.push_back(PortSpec::scalar("min_acceleration", dim::length / dim::angle.pow(2), "min (most negative) d2h/dphi2"));
    info_.outputs.push_back(PortSpec::scalar("accel_angle", dim::angle, "achieved positive-acceleration phase from the start of lift", "deg"));
    info_.outputs.push_back(PortSpec::scalar("min_curvature_radius", dim::length,
                                             "smallest radius of curvature of the contour for the law's own follower (a flat face unless "
                                             "the law was made for a roller); negative where that follower would undercut: cam.contour "
                                             "checks the cam with its follower",
                                             "mm"));
    info_.outputs.push_back(svaj_port("svaj", "lift, velocity, acceleration and jerk over cam angle (and crank angle), curve_points rows"));
    info_.frames = cam_angle_frames();
    info_.notes.push_back(timing_note());
    for (PortSpec& port : lift_event_ports("cam")) info_.outputs.push_back(std::move(port));
    for (auto& p : d.extra_outputs) {
      if (p.kind == ValueKind::scalar) extra_scalars_.push_back(p.name);
      info_.outputs.push_back(std::move(p));
    }
    info_.inputs = std::move(d.extra_inputs);
    info_.output_dependencies = std::move(d.output_dependencies);
    info_.work_counters = {"evaluations"};
    for (auto& c : d.extra_work_counters) info_.work_counters.push_back(std::move(c));
  }

  const NodeInfo& info() const override { return info_; }
  std::optional<std::vector<std::string>> forecast_reads() const override { return reads_; }

  // The law's cost, then the searches over its pieces (the summary and the events: each piece
  // interpolated at summary_items_per_piece points or so, samples raising the start), then the
  // svaj table's points.
  std::optional<WorkForecast> forecast(const ParamSet& params, const InputSizes&) const override {
    // A sweep asks this once per case: one lookup per parameter, one string made.
    const auto value = [&params](std::string_view name) -> const ParamValue* {
      auto it = params.all().find(name);
      return it != params.all().end() ? &it->second : nullptr;
    };
    CamLawCost law = cost_ ? cost_(params) : CamLawCost{};
    if (const ParamValue* ramp = value("ramp"); ramp && ramp->text != "none") law.pieces += 4.0;  // a ramp's pieces each side
    const ParamValue* samples_value = value("samples");
    const double samples = samples_value ? static_cast<double>(static_cast<long>(samples_value->number)) : 16.0;
    const double per_piece = summary_items_per_piece * std::max(1.0, samples / 32.0);
    const double searches = law.pieces * law.search_factor * per_piece;
    const ParamValue* points_value = value("curve_points");
    const double points = points_value ? static_cast<double>(static_cast<long>(points_value->number)) : 0.0;
    WorkForecast f;
    f.items = law.items + searches + points;
    f.memory = law.memory + law.pieces * law.search_factor * summary_bytes_per_piece * std::max(1.0, samples / 32.0) +
               points * svaj_bytes_per_point;
    f.output_size = law.pieces;
    if (!law.driver.empty() && law.items + searches >= points) {
      f.driver = law.driver;
    } else if (points >= searches) {
      f.driver = "curve_points = " + std::to_string(static_cast<long>(points));
    } else {
      f.driver.reserve(48);
      f.driver.append("samples = ").append(std::to_string(static_cast<long>(samples)));
      f.driver.append(" (per piece, ").append(std::to_string(static_cast<long>(law.pieces))).append(" pieces)");
    }
    return f;
  }

  // The note of a contour its own follower would undercut: by how much, the base radius that
  // removes it (the law rebuilt at other base radii, with a stated margin), and what cam.contour
  // checks for the other followers.
  std::string undercut_note(const CamLaw& law, double rho_min, const CamBasics& basics, const ParamSet& params,
                            const RampSpec& ramp, int samples) const {
    const double rr = law.roller_radius();
    std::ostringstream m;
    m.precision(4);
    m << "undercut: under " << (rr > 0.0 ? "its roller" : "a flat-faced follower") << " this cam's contour would be "
      << "undercut, its smallest radius of curvature " << rho_min * 1e3 << " mm (must be > 0)";
    const auto law_at = [&](double r0) -> std::shared_ptr<const CamLaw> {
      CamBasics b = basics;
      b.base_radius = r0;
      OutputSet scratch;
      std::shared_ptr<const CamLaw> l = make_(b, params, scratch);
      if (ramp.type != RampType::none) l = std::make_shared<const RampedLaw>(l, ramp);
      return l;
    };
    if (const auto r_min = smallest_undercut_free_base_radius(law_at, law.base_radius(), samples)) {
      // The limit itself is on the edge (printed to 4 digits it may fall below it): 1 % more, up to 0.1 mm.
      const double suggested = std::ceil(*r_min * 1.01 * 1e4) / 1e4;
      m << "; a base_radius of " << suggested * 1e3 << " mm removes it (the limit " << *r_min * 1e3
        << " mm plus 1 %, rounded up to 0.1 mm)";
    }
    m << ". The cam is not refused here: cam.contour checks the cam with the follower that runs on it (flat, roller, "
         "offset roller, pivoted flat or roller) and refuses an undercut pair";
    return m.str();
  }

  // The law of the parameters, ramps included; `basics` and `ramp` as it was made from them.
  std::shared_ptr<const CamLaw> make_law(const ParamSet& params, const InputSet& inputs, OutputSet& out, EvalContext& ctx,
                                         CamBasics& basics, RampSpec& ramp) const {
    ramp = read_ramp(params);
    const bool has_lift = params.has("max_lift"), has_action = params.has("action_angle");
    return make_law(params, has_lift ? params.number("max_lift") : 0.0, has_lift,
                    has_action ? params.number("action_angle") : 0.0, has_action, params.number("base_radius"), inputs, out,
                    ctx, basics, ramp);
  }
  // The same from the common numbers read (a block reads them from its columns, and gives its
  // prepared factory and the case's index when it has one).
  std::shared_ptr<const CamLaw> make_law(const ParamSet& params, double max_lift, bool has_lift, double action_angle,
                                         bool has_action, double base_radius, const InputSet& inputs, OutputSet& out,
                                         EvalContext& ctx, CamBasics& basics, const RampSpec& ramp,
                                         const CamLawCaseFactory* prepared = nullptr, std::size_t k = 0) const {
    if (ramp.type != RampType::none && !(has_lift && has_action))
      throw NodeError(has_lift ? "action_angle" : "max_lift", "a ramp on this law needs max_lift and action_angle given");
    basics = CamBasics{has_lift ? main_lift(ramp, max_lift, action_angle) : 0.0, action_angle, base_radius, has_lift,
                       has_action, &inputs, &ctx};
    std::shared_ptr<const CamLaw> law = prepared ? (*prepared)(basics, params, k, out) : make_(basics, params, out);
    if (ramp.type != RampType::none) law = std::make_shared<const RampedLaw>(law, ramp);
    return law;
  }

  void evaluate(const ParamSet& params, const InputSet& inputs, OutputSet& out, EvalContext& ctx) const override {
    CamBasics basics;
    RampSpec ramp;
    const std::shared_ptr<const CamLaw> law = make_law(params, inputs, out, ctx, basics, ramp);
    const int samples = static_cast<int>(params.integer("samples"));
    // A sweep that does not read the curvature radius only needs the contour proven free of undercut.
    // So do the peaks and the phase: each is computed only when something reads it.
    const CamSummaryParts parts{ctx.wanted("max_velocity") || ctx.wanted("max_acceleration") || ctx.wanted("min_acceleration"),
                                ctx.wanted("accel_angle"), ctx.wanted("min_curvature_radius")};
    // No undercut check here: whether a contour can be followed depends on the follower, and is
    // checked where cam and follower meet (cam.contour, docs/methods/followers.md).
    const CamSummary s = summarize(*law, samples, parts);
    ctx.report_work("evaluations", static_cast<double>(s.evaluations));
    // The contour is not refused here, but an undercut does not pass unseen: summarize proves the
    // contour convex or measures its smallest radius, so the note costs nothing unless it is due.
    if (s.min_curvature_radius <= 0.0) out.note(undercut_note(*law, s.min_curvature_radius, basics, params, ramp, samples));
    out.set("law", Value::handle(law));
    out.set_scalar("max_lift", law->max_lift());
    if (s.peaks_known) {
      out.set_scalar("max_velocity", s.max_velocity);
      out.set_scalar("max_acceleration", s.max_acceleration);
      out.set_scalar("min_acceleration", s.min_acceleration);
    }
    if (s.phase_known) out.set_scalar("accel_angle", s.accel_angle);
    if (s.curvature_exact) out.set_scalar("min_curvature_radius", s.min_curvature_radius);
    // The curves and events cost hundreds of evaluations: made only when something reads them.
    if (ctx.wanted("svaj")) {
      out.set("svaj", Value::table(svaj_table(*law, static_cast<int>(params.integer("curve_points")))));
      ctx.report_work("evaluations", static_cast<double>(params.integer("curve_points")));
    }
    if (lift_events_wanted(ctx)) {
      long evaluations = 0;
      set_lift_events(out, ctx, params, [&](double phi) { return law->at(phi).lift; }, law->knots(), law->max_lift(), "cam", samples,
                      evaluations);
      ctx.report_work("evaluations", static_cast<double>(evaluations));
    }
  }

  // Blocks: the law and the scalar outputs, by the same functions as evaluate(); the svaj table,
  // the events and laws that read inputs stay with single evaluations. An undercut note is not
  // made (a sweep's rows carry no notes): the summary runs only for the outputs read.
  bool block_supported(const BlockRequest& request) const override {
    if (!info_.inputs.empty()) return false;
    for (const std::string& output : request.wanted)
      if (!block_output(output)) return false;
    for (const std::string& name : request.varied)
      if (name == "samples" || name == "curve_points") return false;
    return true;
  }

  void evaluate_block(const BlockParams& p, const BlockInputs&, BlockOutputs& out, BlockCases& cases,
                      EvalContext& ctx) const override {
    const InputSet no_inputs;
    std::vector<std::shared_ptr<const CamLaw>> laws(cases.size());
    const CamSummaryParts parts{out.scalar("max_velocity") || out.scalar("max_acceleration") || out.scalar("min_acceleration"),
                                out.scalar("accel_angle") != nullptr, out.scalar("min_curvature_radius") != nullptr};
    const bool summary_wanted = parts.peaks || parts.phase || parts.curvature;
    // The law-specific scalar outputs read downstream (three-arc radii, ...), into one set for the
    // block: each case finds its slots made (no allocation) and marked unset (a handle's kind) until
    // the factory sets them.
    OutputSet extra;
    std::vector<std::pair<Value*, double*>> extras;
    for (const std::string& port : extra_scalars_)
      if (double* column = out.scalar(port)) extras.emplace_back(&extra.slot(port), column);
    // The columns, found once for the block (null: not read downstream).
    double* const max_lift = out.scalar("max_lift");
    double* const peak_columns[] = {out.scalar("max_velocity"), out.scalar("max_acceleration"), out.scalar("min_acceleration"),
                                    out.scalar("accel_angle"), out.scalar("min_curvature_radius")};
    double evaluations = 0.0;
    // The ramp is read once for the block when no case changes it (a refusal stays per case).
    const bool ramp_varies = p.varies("ramp_height") || p.varies("ramp_length");
    std::optional<RampSpec> block_ramp;
    // The common numbers by column, and which are given, read once for the block (as make_law reads them).
    const bool has_lift = p.fixed().has("max_lift"), has_action = p.fixed().has("action_angle");
    const BlockColumn lift_column = has_lift ? p.number("max_lift") : BlockColumn{};
    const BlockColumn action_column = has_action ? p.number("action_angle") : BlockColumn{};
    const BlockColumn radius_column = p.number("base_radius");
    // The law's own preparation for the block, where it has one (else its factory per case).
    CamLawCaseFactory prepared;
    if (prepare_block_) {
      try {
        prepared = prepare_block_(p);
      } catch (const NodeError&) {
        prepared = nullptr;  // each case alone says why
      }
    }
    for_each_live_case(cases, [&](std::size_t k) {
      const ParamSet& params = p.of_case(k);
      CamBasics basics;
      RampSpec ramp;
      if (!ramp_varies && !block_ramp) block_ramp = read_ramp(params);
      ramp = ramp_varies ? read_ramp(params) : *block_ramp;
      for (const auto& [slot, column] : extras) *slot = Value::handle(nullptr);
      laws[k] = make_law(params, has_lift ? lift_column[k] : 0.0, has_lift, has_action ? action_column[k] : 0.0, has_action,
                         radius_column[k], no_inputs, extra, ctx, basics, ramp, prepared ? &prepared : nullptr, k);
      const CamLaw& law = *laws[k];
      if (max_lift) max_lift[k] = law.max_lift();
      for (const auto& [slot, column] : extras) {
        if (slot->kind() != ValueKind::scalar) {
          cases.fail(k);  // not made for this case: the single evaluation says why
          return;
        }
        column[k] = slot->as_scalar();
      }
      if (!summary_wanted) return;
      const CamSummary s = summarize(law, static_cast<int>(params.integer("samples")), parts);
      evaluations += static_cast<double>(s.evaluations);
      const auto put = [&](double* column, bool known, double value) {
        if (column) {
          if (!known) return cases.fail(k);
          column[k] = value;
        }
      };
      put(peak_columns[0], s.peaks_known, s.max_velocity);
      put(peak_columns[1], s.peaks_known, s.max_acceleration);
      put(peak_columns[2], s.peaks_known, s.min_acceleration);
      put(peak_columns[3], s.phase_known, s.accel_angle);
      put(peak_columns[4], s.curvature_exact, s.min_curvature_radius);
    });
    ctx.report_work("evaluations", evaluations);
    out.set_handle("law", std::make_shared<const CamLawBlock>(std::move(laws)));
  }

 private:
  // The outputs a block makes: the law, its common scalars and the law's own scalars.
  bool block_output(const std::string& port) const {
    for (const char* common : {"law", "max_lift", "max_velocity", "max_acceleration", "min_acceleration", "accel_angle",
                               "min_curvature_radius"})
      if (port == common) return true;
    return std::find(extra_scalars_.begin(), extra_scalars_.end(), port) != extra_scalars_.end();
  }

  NodeInfo info_;
  std::vector<std::string> extra_scalars_;  // the law's own scalar outputs (CamLawDefinition::extra_outputs)
  CamLawFactory make_;
  CamLawCostFunction cost_;
  CamLawBlockFactory prepare_block_;
  bool derived_ = false;
  std::optional<std::vector<std::string>> reads_;  // forecast_reads()
};

}  // namespace

std::shared_ptr<const NodeType> make_cam_node_type(CamLawDefinition definition) {
  return std::make_shared<const CamNodeType>(std::move(definition));
}

}  // namespace mechgraph::cams
