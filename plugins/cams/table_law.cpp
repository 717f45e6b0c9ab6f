#include "table_law.hpp"

#include "table_cost.hpp"

#include <mechgraph/bounded_read.hpp>
#include <mechgraph/domain/cam_curves.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/numerics/piecewise.hpp>
#include <mechgraph/units.hpp>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>

namespace mechgraph::cams {
namespace {

constexpr double pi = std::numbers::pi;

std::string at_line(const std::string& source, int line) { return source + ":" + std::to_string(line) + ": "; }

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

// Splits a data line into fields: on ',' or ';' if the line has either, else on blanks.
std::vector<std::string_view> fields_of(std::string_view line) {
  std::vector<std::string_view> out;
  const bool delimited = line.find_first_of(",;") != std::string_view::npos;
  std::size_t i = 0;
  while (i <= line.size()) {
    if (delimited) {
      const std::size_t j = std::min(line.find_first_of(",;", i), line.size());
      out.push_back(trim(line.substr(i, j - i)));
      i = j + 1;
    } else {
      i = line.find_first_not_of(" \t", i);
      if (i == std::string_view::npos) break;
      const std::size_t j = std::min(line.find_first_of(" \t", i), line.size());
      out.push_back(line.substr(i, j - i));
      i = j;
    }
  }
  return out;
}

bool parse_number(std::string_view field, double& value) {
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  if (field.empty()) return false;
  const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
  return ec == std::errc() && ptr == field.data() + field.size() && std::isfinite(value);
}

// A fixed pseudo-random sequence in [0, 1) (splitmix64), so the noise estimate is reproducible.
class UniformSequence {
 public:
  double next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t state_ = 19;
};

// Formats a number with `digits` significant digits.
std::string g(double v, int digits = 3) {
  std::ostringstream m;
  m.precision(digits);
  m << v;
  return m.str();
}

// A length for a note, in um below 0.1 mm, else in mm.
std::string length_text(double metres) {
  return std::abs(metres) < 1e-4 ? g(metres * 1e6) + " um" : g(metres * 1e3) + " mm";
}

}  // namespace

LiftTable parse_lift_table(std::string_view text, const std::string& source, double angle_scale, double lift_scale) {
  LiftTable table;
  table.source = source;
  table.lift_scale = lift_scale;
  bool header_allowed = true;
  int line_number = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    line = trim(line);
    if (line.empty()) continue;
    const auto fields = fields_of(line);
    double angle = 0.0, lift = 0.0;
    const bool numeric = fields.size() == 2 && parse_number(fields[0], angle) && parse_number(fields[1], lift);
    if (!numeric) {
      if (header_allowed) {  // a header line before the first row
        header_allowed = false;
        continue;
      }
      // The file may be anything a scene names: quote one offending cell, shortened, never the line.
      std::ostringstream m;
      m << at_line(source, line_number) << "expected two finite numbers (angle, lift), found ";
      if (fields.size() != 2) {
        m << fields.size() << " field" << (fields.size() == 1 ? "" : "s");
      } else {
        double ignored = 0.0;
        const std::string_view bad = parse_number(fields[0], ignored) ? fields[1] : fields[0];
        m << quoted_text_excerpt(bad, 80);
      }
      throw NodeError("file", m.str());
    }
    header_allowed = false;
    if (lift < 0.0) {
      std::ostringstream m;
      m << at_line(source, line_number) << "negative lift " << lift << "; the lift is measured from the base circle";
      throw NodeError("file", m.str());
    }
    const LiftTableRow row{angle * angle_scale, lift * lift_scale, line_number};
    if (!table.rows.empty() && !(row.angle > table.rows.back().angle)) {
      std::ostringstream m;
      m << at_line(source, line_number) << "angle " << angle << " does not increase (line " << table.rows.back().line
        << " has " << table.rows.back().angle / angle_scale << "); the angles must increase strictly";
      throw NodeError("file", m.str());
    }
    table.rows.push_back(row);
  }
  return table;
}

LiftTable read_lift_table(const std::string& path, double angle_scale, double lift_scale) {
  // A scene from someone else may name a folder, a FIFO, /dev/zero or a huge file: only a regular
  // file up to lift_table_limit is read, with that bound.
  std::string text;
  try {
    text = read_bounded_file(path, lift_table_limit);
  } catch (const FileReadError& e) {
    throw NodeError("file", std::string("the lift table: ") + e.what());
  }
  return parse_lift_table(text, path, angle_scale, lift_scale);
}

LiftTable listed_lift_table(const ParamSet& params) {
  if (!params.has("angles") || !params.has("lifts"))
    throw NodeError(params.has("angles") ? "lifts" : "angles", "angles and lifts go together: give both lists");
  const std::vector<double>& angles = params.numbers("angles");
  const std::vector<double>& lifts = params.numbers("lifts");
  if (angles.size() != lifts.size())
    throw NodeError("lifts", "lifts has " + std::to_string(lifts.size()) + " values, angles " + std::to_string(angles.size()) +
                                 "; they must be as long");
  LiftTable table;
  table.source = "lifts";
  table.lift_scale = 0.0;  // numbers, not printed digits: no resolution to read from them
  for (std::size_t i = 0; i < angles.size(); ++i)  // "line" i + 1 of the lists: the (i + 1)-th pair
    table.rows.push_back({angles[i], lifts[i], static_cast<int>(i + 1)});
  return table;
}

double lift_quantum(const LiftTable& table) {
  // Every lift as printed (in the file's unit) a whole multiple of 10^-k, k = 0 .. 6, the largest
  // such quantum; a parsed decimal is within a few ulps of it.
  int with_lift = 0;
  for (const LiftTableRow& r : table.rows) with_lift += r.lift > 0.0 ? 1 : 0;
  if (with_lift < 8 || !(table.lift_scale > 0.0)) return 0.0;
  for (int k = 0; k <= 6; ++k) {
    const double q = std::pow(10.0, -k);
    const bool whole = std::all_of(table.rows.begin(), table.rows.end(), [&](const LiftTableRow& r) {
      const double units = r.lift / table.lift_scale / q;
      return std::abs(units - std::round(units)) <= 1e-6;
    });
    if (whole) return q * table.lift_scale;
  }
  return 0.0;
}

TableLaw::TableLaw(const LiftTable& table, double base_radius, const TableSmoothingRequest& smoothing)
    : source_(table.source), method_(smoothing.method), base_radius_(base_radius) {
  const std::string& src = table.source;
  if (!(std::isfinite(base_radius) && base_radius > 0.0))
    throw NodeError("base_radius", "base_radius must be positive and finite");
  const auto& rows = table.rows;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!std::isfinite(rows[i].angle) || !std::isfinite(rows[i].lift) || rows[i].lift < 0.0)
      throw NodeError("file", at_line(src, rows[i].line) + "the lift must be finite and not negative");
    if (i > 0 && !(rows[i].angle > rows[i - 1].angle))
      throw NodeError("file", at_line(src, rows[i].line) + "the angles must increase strictly");
  }
  // The event: from the last leading zero-lift row to the first trailing zero-lift row.
  std::size_t first = 0, last = rows.size();
  while (first + 1 < rows.size() && rows[first].lift == 0.0 && rows[first + 1].lift == 0.0) ++first;
  while (last >= 2 && rows[last - 1].lift == 0.0 && rows[last - 2].lift == 0.0) --last;
  if (rows.empty() || last <= first || std::all_of(rows.begin(), rows.end(), [](const LiftTableRow& r) { return r.lift == 0.0; }))
    throw NodeError("file", src + ": the table has no lift (no row with lift > 0)");
  if (rows[first].lift != 0.0) {
    std::ostringstream m;
    m << at_line(src, rows[first].line) << "the lift must start from zero (the base circle), this first row has "
      << rows[first].lift * 1e3 << " mm; add the rows before the start of lift";
    throw NodeError("file", m.str());
  }
  if (rows[last - 1].lift != 0.0) {
    std::ostringstream m;
    m << at_line(src, rows[last - 1].line) << "the lift must return to zero (the base circle), this last row has "
      << rows[last - 1].lift * 1e3 << " mm; add the rows after the end of lift";
    throw NodeError("file", m.str());
  }
  const std::size_t n = last - first;
  if (n < 6) {
    std::ostringstream m;
    m << src << ": the lift event has " << n << " rows (lines " << rows[first].line << " .. " << rows[last - 1].line
      << "); the quintic interpolation needs at least 6";
    throw NodeError("file", m.str());
  }
  if (rows[first].angle < -pi || rows[last - 1].angle > pi) {
    std::ostringstream m;
    m << src << ": the lift event (lines " << rows[first].line << " .. " << rows[last - 1].line
      << ") must lie within -180 .. 180 deg from the nose (angles counted from the start of lift? set "
         "angle_origin: start_of_lift)";
    throw NodeError("file", m.str());
  }
  first_line_ = rows[first].line;
  last_line_ = rows[last - 1].line;
  std::vector<int> lines;
  for (std::size_t i = first; i < last; ++i) {
    row_angles_.push_back(rows[i].angle);
    row_lifts_.push_back(rows[i].lift);
    lines.push_back(rows[i].line);
  }
  const std::vector<double>& x = row_angles_;
  const std::vector<double>& y = row_lifts_;
  const int m = static_cast<int>(n);
  TableDiagnostics& d = diagnostics_;
  d.rows = m;
  {
    std::vector<double> steps;
    for (int i = 1; i < m; ++i) steps.push_back(x[i] - x[i - 1]);
    std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
    d.row_step = steps[steps.size() / 2];
  }
  if (smoothing.resolution < 0.0 || !std::isfinite(smoothing.resolution))
    throw NodeError("resolution", "resolution must be positive and finite");
  d.resolution = smoothing.resolution;
  if (!(d.resolution > 0.0)) {
    d.resolution = lift_quantum(table);
    d.resolution_detected = d.resolution > 0.0;
  }

  if (d.resolution > 0.0) {
    int same = 0;
    for (int i = 1; i < m; ++i) same += std::abs(y[i] - y[i - 1]) < 0.5 * d.resolution ? 1 : 0;
    d.same_lift_share = static_cast<double>(same) / (m - 1);
  }

  // The law: the interpolant, or the smoothing spline at the chosen lambda.
  std::optional<QuinticSmoother> smoother;
  if (method_ == TableSmoothing::none) {
    pieces_ = interpolate_quintic(x, y, src + ": ");
  } else {
    smoother.emplace(x, y);
    if (method_ == TableSmoothing::resolution) {
      if (!(d.resolution > 0.0))
        throw NodeError("resolution",
                        src + ": smoothing: resolution needs the measuring resolution (the last digit of the lift "
                              "column, e.g. resolution: 1 um); the lifts are not whole multiples of any of 1 .. 1e-6 "
                              "file units, so it cannot be read from the file. Set resolution, or use smoothing: gcv");
      // Discrepancy principle: rounding to r leaves errors uniform in +-r/2, RMS r / sqrt(12).
      d.lambda = smoother->lambda_for_rms(d.resolution / std::sqrt(12.0), d.lambda_at_limit, d.work);
    } else {
      d.lambda = smoother->lambda_by_gcv(d.lambda_at_limit, d.work);
    }
    const QuinticSmoother::Fit fit = smoother->fit_nonnegative(d.lambda, d.work);
    d.dof = fit.dof;
    d.held_at_zero = fit.held_at_zero;
    pieces_ = smoother->pieces(fit.coefficients);
  }
  for (const auto& c : pieces_.taylor)
    for (double v : c)
      if (!std::isfinite(v)) throw NodeError("file", src + ": the spline through the table overflowed");

  // Residuals over the inner rows (the ends are zero by construction).
  double sum = 0.0;
  for (int i = 1; i + 1 < m; ++i) {
    const double r = y[i] - pieces_.at(x[i])[0];
    sum += r * r;
    if (std::abs(r) > d.residual_max) {
      d.residual_max = std::abs(r);
      d.residual_max_angle = x[i];
      d.residual_max_line = lines[i];
    }
  }
  d.residual_rms = std::sqrt(sum / (m - 2));
  d.max_abs_acceleration = pieces_.max_abs_derivative(2);
  d.max_jerk = pieces_.max_abs_derivative(3);

  // The noise of the resolution in h'' and h''': the same linear operator (interpolant, or the
  // unconstrained smoother at the same lambda) applied to rounding errors uniform in +-r/2, its
  // h'' and h''' as RMS over the event (their extremes reach some 2 to 3 times that, more in the
  // end intervals of the interpolant).
  d.noise_resolution = d.resolution;
  if (!(d.noise_resolution > 0.0) && method_ == TableSmoothing::gcv && d.dof < m - 2 - 0.5) {
    d.noise_resolution = std::sqrt(12.0 * d.residual_rms * d.residual_rms * (m - 2) / (m - 2 - d.dof));
    d.noise_resolution_estimated = true;
  }
  if (d.noise_resolution > 0.0) {
    UniformSequence uniform;
    std::vector<double> e(m, 0.0);
    for (int i = 1; i + 1 < m; ++i) e[i] = d.noise_resolution * (uniform.next() - 0.5);
    const QuinticPieces noise = smoother ? smoother->pieces(smoother->smooth(e, d.lambda, d.work))
                                         : interpolate_quintic(x, e, src + ": ");
    d.acceleration_noise = noise.rms_derivative(2);
    d.jerk_noise = noise.rms_derivative(3);
  }

  // Maximum of the law, over each polynomial piece.
  long evaluations = 0;
  const auto best = numerics::maximize_piecewise([this](double a) { return at(a).lift; }, pieces_.breaks, 12, evaluations);
  max_lift_ = best.value;
  max_lift_angle_ = best.x;
}

LiftDerivatives TableLaw::evaluate_in_event(double phi) const {
  const auto s = pieces_.at(phi);
  return {s[0], s[1], s[2], s[3]};
}

std::vector<std::string> TableLaw::notes() const {
  const TableDiagnostics& d = diagnostics_;
  std::vector<std::string> out;
  const std::string step = g(d.row_step * 180.0 / pi) + " deg rows";
  std::string resolution_said;
  if (d.resolution > 0.0)
    resolution_said = length_text(d.resolution) + (d.resolution_detected ? " (every lift a multiple of it)" : " (stated)");
  // How far the resolution alone moves h'' and h''' (RMS over the event), against their peaks.
  auto noise_said = [&]() {
    std::ostringstream m;
    m << " h'' by " << g(d.acceleration_noise * 1e3) << " mm/rad^2 RMS ("
      << g(100.0 * d.acceleration_noise / std::max(d.max_abs_acceleration, 1e-300), 2)
      << " % of its peak; a flat follower's radius of curvature r0 + h + h'' by as much) and h''' by "
      << g(d.jerk_noise * 1e3) << " mm/rad^3 RMS (" << g(100.0 * d.jerk_noise / std::max(d.max_jerk, 1e-300), 2)
      << " % of its peak)";
    return m.str();
  };
  if (d.same_lift_share > 0.05) {
    out.push_back(g(100.0 * d.same_lift_share, 2) + " % of neighbouring rows have the same lift: the rows are closer (" +
                  step + ") than a resolution of " + length_text(d.resolution) +
                  " tells apart, so their rounding errors form a staircase rather than independent noise; the " +
                  "noise estimates assume independent errors and the smoothing may follow the steps. A table with "
                  "fewer rows (every few rows of this one) would be read more faithfully");
  }
  const bool acceleration_noisy = d.acceleration_noise > 0.01 * d.max_abs_acceleration;
  const bool jerk_noisy = d.jerk_noise > 0.1 * d.max_jerk;
  if (method_ == TableSmoothing::none) {
    if (d.resolution > 0.0 && (acceleration_noisy || jerk_noisy)) {
      std::string meaningless = acceleration_noisy && jerk_noisy ? "the radius of curvature, acceleration and jerk"
                                : acceleration_noisy             ? "the radius of curvature and acceleration"
                                                                 : "the jerk";
      out.push_back("lift table rounded to " + resolution_said + ", " + step + ": the rounding alone moves" +
                    noise_said() + ", so " + meaningless +
                    " of the unsmoothed table are not meaningful; set smoothing: resolution (or gcv)");
    }
    return out;
  }
  std::ostringstream m;
  m << "lift table smoothed (smoothing: " << (method_ == TableSmoothing::resolution ? "resolution" : "gcv");
  if (d.resolution > 0.0) m << ", resolution " << resolution_said;
  m << "): lambda " << g(d.lambda) << ", " << g(d.dof) << " effective degrees of freedom for " << d.rows - 2
    << " rows (" << step << "); residual RMS " << length_text(d.residual_rms);
  if (d.resolution > 0.0) m << " (rounding alone: " << length_text(d.resolution / std::sqrt(12.0)) << ")";
  m << ", max " << length_text(d.residual_max) << " at " << g(d.residual_max_angle * 180.0 / pi, 4) << " deg";
  if (d.held_at_zero > 0) m << "; " << d.held_at_zero << " B-spline coefficients held at zero to keep the lift >= 0";
  if (d.noise_resolution > 0.0) {
    m << "; " << (d.noise_resolution_estimated ? "noise of " + length_text(d.noise_resolution) +
                                                     " (estimated from the residual, as if rounded to it)"
                                               : std::string("the resolution"))
      << " alone moves the smoothed" << noise_said();
  }
  out.push_back(m.str());
  if (d.lambda_at_limit) {
    const bool lower = d.lambda <= QuinticSmoother::lambda_min;
    const bool by_resolution = method_ == TableSmoothing::resolution;
    out.push_back(std::string("the smoothing's lambda is at the ") + (lower ? "lower" : "upper") + " end of its range (" +
                  g(d.lambda) + "): " +
                  (lower ? (by_resolution ? "the law interpolates the rows, which scatter more than the resolution "
                                            "says (is the resolution right?)"
                                          : "cross-validation finds no noise to remove, the law interpolates the rows")
                         : (by_resolution ? "the law is as smooth as it goes and still fits the rows closer than the "
                                            "resolution says they can be (is the resolution right?)"
                                          : "cross-validation asks for the smoothest law on offer")));
  }
  if (d.resolution > 0.0 && d.residual_max > 2.0 * d.resolution) {
    std::ostringstream s;
    s << at_line(source_, d.residual_max_line) << "the row at " << g(d.residual_max_angle * 180.0 / pi, 4) << " deg is "
      << length_text(d.residual_max) << " off the smoothed law, " << g(d.residual_max / d.resolution, 2)
      << " times the resolution: a step, a bad row or a feature the smoothing does not follow";
    out.push_back(s.str());
  }
  return out;
}

namespace {

// The law against a master law at the table's angles within one turn (-180 .. 180 deg): the
// law's deviation and the rows' own, unsmoothed.
void set_master_deviation(const TableLaw& law, const LiftTable& table, const InputSet& inputs, OutputSet& out) {
  const auto master = inputs.handle<CamLaw>("master");
  Table t;
  t.axis = {"cam_angle", dim::angle, {}, "deg"};
  Table::Column deviation{"deviation", dim::length, {}, "um"}, row_deviation{"row_deviation", dim::length, {}, "um"};
  double sum = 0.0, largest = 0.0;
  for (const LiftTableRow& r : table.rows) {
    if (r.angle < -pi || r.angle >= pi) continue;
    const double nominal = master->at(r.angle).lift;
    const double dev = law.at(r.angle).lift - nominal;
    t.axis.values.push_back(r.angle);
    deviation.values.push_back(dev);
    row_deviation.values.push_back(r.lift - nominal);
    sum += dev * dev;
    largest = std::max(largest, std::abs(dev));
  }
  if (t.axis.values.empty()) throw NodeError("master", "the table has no row within -180 .. 180 deg to compare");
  out.set_scalar("master_deviation_rms", std::sqrt(sum / static_cast<double>(t.axis.values.size())));
  out.set_scalar("master_deviation_max", largest);
  t.channels = {std::move(deviation), std::move(row_deviation)};
  out.set("master_deviation", Value::table(std::move(t)));
}

}  // namespace

CamLawDefinition table_law_definition() {
  CamLawDefinition d;
  d.type = "cam.table";
  // 2: smoothing, resolution, the master input, residual and noise outputs; 3: angles and lifts
  // (the table as lists, e.g. numpy arrays from the Python module) instead of the file
  d.version = 3;
  d.summary =
      "tabulated lift from a CSV file (cam angle, lift), quintic spline interpolation or, for measured tables, a "
      "penalised quintic smoothing spline; lift and event from the file";
  d.derives_lift_and_action = true;
  // An example table for the conformance kit (`mechgraph plugin-test`), which evaluates the type
  // with its defaults and examples: h = 9 mm cos^2(pi phi / 130 deg) over -65 .. 65 deg, every
  // 2.5 deg (smooth, zero with zero slope at both ends; the common examples' lift and action angle).
  std::vector<double> example_angles, example_lifts;
  for (int i = -26; i <= 26; ++i) {
    const double phi = 2.5 * i * pi / 180.0, c = std::cos(pi * phi / (130.0 * pi / 180.0));
    example_angles.push_back(phi);
    example_lifts.push_back(std::abs(i) == 26 ? 0.0 : 9e-3 * c * c);
  }
  ParamSpec angles = ParamSpec::number_list("angles", dim::angle,
                                            "the table's cam angles as a list instead of a file (with lifts; the Python module "
                                            "passes numpy arrays here); the same checks as the file's rows",
                                            "deg")
                         .optional();
  angles.example_value = ParamValue::of_list(std::move(example_angles));
  ParamSpec lifts = ParamSpec::number_list("lifts", dim::length, "the table's lifts, one per angle (with angles)", "mm").optional();
  lifts.example_value = ParamValue::of_list(std::move(example_lifts));
  d.params = {
      ParamSpec::text("file",
                      "CSV lift table: cam angle, lift; ',' ';' or blank separated, '#' comments, one header line "
                      "allowed; a relative path is taken from the scene file's folder. max_lift and action_angle come "
                      "from it; if given they must agree (0.1 %, 1e-4 deg). Give file, or angles and lifts")
          .as_path()
          .optional(),
      angles,
      lifts,
      ParamSpec::choice("angle_origin", {"nose", "start_of_lift"},
                        "where the table's angles are counted from: nose (0 at the top, the lift event around it), or "
                        "start_of_lift (0 where the lift begins; the event is then centred on 0)")
          .with_default("nose"),
      ParamSpec::text("angle_unit", "unit of the table's angle column").with_default(std::string("deg")),
      ParamSpec::text("lift_unit", "unit of the table's lift column").with_default(std::string("mm")),
      ParamSpec::choice("smoothing", {"none", "resolution", "gcv"},
                        "none: the quintic spline through every row (for exact or exported tables); resolution: a "
                        "penalised quintic spline (penalty on the integral of h''''^2, the rate of change of the "
                        "jerk) whose residual RMS equals the rounding noise resolution/sqrt(12) (for measured "
                        "tables); gcv: the same spline, its smoothing chosen by generalised cross-validation (when "
                        "the resolution is not known)")
          .with_default("none"),
      ParamSpec::number("resolution", dim::length,
                        "the measuring machine's last printed digit of the lift (e.g. 1 um); default: read from the "
                        "file when every lift is a whole multiple of 1, 0.1, ... or 1e-6 of its unit. Sets the "
                        "smoothing of smoothing: resolution, and the note when the table is too coarse for curvature "
                        "and jerk",
                        "um")
          .optional()
          .positive()
          .at_most(1e-3)
          .because("> 0: a digit's size; <= 1 mm: a measuring machine's last digit of a valve lift"),
  };
  d.extra_inputs = {
      PortSpec::handle("master", std::string(CamLaw::kind_name),
                       "a master (design) law to compare the table with, at the table's angles")
          .optional_port(),
  };
  d.extra_outputs = {
      PortSpec::scalar("residual_rms", dim::length, "RMS of the rows minus the law (inner rows of the event)", "um"),
      PortSpec::scalar("residual_max", dim::length, "largest |row - law| (inner rows of the event)", "um"),
      PortSpec::scalar("max_jerk", dim::length / dim::angle.pow(3), "max |d3h/dphi3| over the event"),
      PortSpec::scalar("smoothing_lambda", dim::none,
                       "the smoothing's lambda: weight of the integral of h''''^2, in units of the mean row step^7 "
                       "(smoothing resolution or gcv only)"),
      PortSpec::scalar("smoothing_dof", dim::none,
                       "effective degrees of freedom of the smoothing spline, the trace of its influence matrix "
                       "(smoothing resolution or gcv only)"),
      PortSpec::scalar("lift_resolution", dim::length, "the resolution used: stated, or read from the file (when known)",
                       "um"),
      PortSpec::scalar("acceleration_noise", dim::length / dim::angle.pow(2),
                       "RMS over the event of the change of h'' that rounding the rows to the resolution alone makes "
                       "(when a resolution is known or, with gcv, estimated)"),
      PortSpec::scalar("jerk_noise", dim::length / dim::angle.pow(3),
                       "RMS over the event of the change of h''' that rounding the rows to the resolution alone makes "
                       "(when a resolution is known or, with gcv, estimated)"),
      PortSpec::scalar("master_deviation_rms", dim::length,
                       "RMS of the law minus the master law at the table's angles (master connected only)", "um"),
      PortSpec::scalar("master_deviation_max", dim::length,
                       "largest |law - master| at the table's angles (master connected only)", "um"),
      PortSpec::table("master_deviation",
                      "over the table's angles: deviation (law - master) and row_deviation (row - master) (master "
                      "connected only)")
          .presented(over_cam_angle()),
  };
  d.output_dependencies = {{"master_deviation_rms", {"master"}}, {"master_deviation_max", {"master"}}, {"master_deviation", {"master"}}};
  d.extra_work_counters = {"solves", "iterations"};
  d.cost = table_cost;
  d.cost_reads = std::vector<std::string>{"angles", "file", "smoothing"};  // table_rows and table_cost
  d.make = [](const CamBasics& basics, const ParamSet& params, OutputSet& out) -> std::shared_ptr<const CamLaw> {
    auto scale_of = [&](const char* name, const char* fallback, Dimension expected, const char* what) {
      const std::string text = params.has(name) ? params.text(name) : std::string(fallback);
      UnitScale u;
      try {
        u = parse_unit(text);
      } catch (const UnitError& e) {
        throw NodeError(name, std::string(name) + " '" + text + "': " + e.what());
      }
      if (!(u.dimension == expected) || u.offset != 0.0)
        throw NodeError(name, std::string(name) + " '" + text + "' is not " + what + " unit (e.g. " +
                                  (expected == dim::angle ? "deg, rad" : "mm, m, in") + ")");
      return u.scale;
    };
    const double angle_scale = scale_of("angle_unit", "deg", dim::angle, "an angle");
    const double lift_scale = scale_of("lift_unit", "mm", dim::length, "a length");
    const bool listed = params.has("angles") || params.has("lifts");
    if (listed == params.has("file"))
      throw NodeError("file", listed ? "give the table once: file, or angles and lifts, not both"
                                     : "no table: give file, or angles and lifts");
    const std::string path = listed ? std::string("lifts") : params.text("file");
    LiftTable table = listed ? listed_lift_table(params) : read_lift_table(path, angle_scale, lift_scale);
    if (params.text("angle_origin") == "start_of_lift" && !table.rows.empty()) {
      // Centre the lift event (between the last zero row before it and the first after) on 0.
      std::size_t first = 0, last = table.rows.size() - 1;
      while (first + 1 < table.rows.size() && table.rows[first + 1].lift == 0.0) ++first;
      while (last > 0 && table.rows[last - 1].lift == 0.0) --last;
      if (first < last) {
        const double middle = 0.5 * (table.rows[first].angle + table.rows[last].angle);
        for (LiftTableRow& r : table.rows) r.angle -= middle;
      }
    }
    TableSmoothingRequest smoothing;
    const std::string method = params.text("smoothing");
    smoothing.method = method == "resolution" ? TableSmoothing::resolution
                       : method == "gcv"      ? TableSmoothing::gcv
                                              : TableSmoothing::none;
    if (params.has("resolution")) smoothing.resolution = params.number("resolution");
    std::shared_ptr<const TableLaw> law;
    try {
      law = std::make_shared<const TableLaw>(table, basics.base_radius, smoothing);
    } catch (const NodeError& e) {
      if (!listed || e.parameter() != "file") throw;
      throw NodeError("lifts", e.what());  // the rows came from the lists: name them, not the file
    }
    const TableDiagnostics& diag = law->diagnostics();
    if (basics.context) {
      basics.context->report_work("solves", static_cast<double>(diag.work.solves));
      basics.context->report_work("iterations", static_cast<double>(diag.work.iterations));
    }
    out.set_scalar("residual_rms", diag.residual_rms);
    out.set_scalar("residual_max", diag.residual_max);
    out.set_scalar("max_jerk", diag.max_jerk);
    if (smoothing.method != TableSmoothing::none) {
      out.set_scalar("smoothing_lambda", diag.lambda);
      out.set_scalar("smoothing_dof", diag.dof);
    }
    if (diag.resolution > 0.0) out.set_scalar("lift_resolution", diag.resolution);
    if (diag.noise_resolution > 0.0) {
      out.set_scalar("acceleration_noise", diag.acceleration_noise);
      out.set_scalar("jerk_noise", diag.jerk_noise);
    }
    for (std::string& note : law->notes()) out.note(path + ": " + note);
    if (basics.inputs && basics.inputs->count("master") > 0) set_master_deviation(*law, table, *basics.inputs, out);

    const double span = law->event_end() - law->event_begin();
    if (basics.has_action_angle && !(std::abs(span - basics.action_angle) <= 1e-4 * pi / 180.0)) {
      std::ostringstream m;
      m.precision(10);
      m << path << ": the table's lift event spans " << span * 180.0 / pi << " deg ("
        << law->event_begin() * 180.0 / pi << " .. " << law->event_end() * 180.0 / pi << " deg, lines "
        << law->first_line() << " .. " << law->last_line() << "), action_angle is " << basics.action_angle * 180.0 / pi
        << " deg; they must agree within 1e-4 deg";
      throw NodeError("action_angle", m.str());
    }
    if (basics.has_max_lift && !(std::abs(law->max_lift() - basics.max_lift) <= 1e-3 * basics.max_lift)) {
      std::ostringstream m;
      m.precision(10);
      m << path << ": the table's maximum lift is " << law->max_lift() * 1e3 << " mm (at "
        << law->max_lift_angle() * 180.0 / pi << " deg), max_lift asks for " << basics.max_lift * 1e3
        << " mm (net of the ramp's share, if a ramp is set); they must agree within 0.1 %";
      throw NodeError("max_lift", m.str());
    }
    return law;
  };
  return d;
}

}  // namespace mechgraph::cams
