#include "table_law.hpp"

#include <mechgraph/bounded_read.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/numerics/piecewise.hpp>
#include <mechgraph/units.hpp>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>
#include <sstream>

namespace mechgraph::cams {
namespace {

constexpr double pi = std::numbers::pi;
constexpr int degree = 5;

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

// ---- Quintic B-spline interpolation (de Boor) -------------------------------------------------

// Values of the d+1 B-splines of degree d that are nonzero on the knot span mu (t[mu] <= x <=
// t[mu+1]), B_{mu-d} .. B_mu, by the Cox-de Boor recurrence.
std::array<double, degree + 1> basis(const std::vector<double>& t, int mu, int d, double x) {
  std::array<double, degree + 1> N{};
  std::array<double, degree + 1> left{}, right{};
  N[0] = 1.0;
  for (int j = 1; j <= d; ++j) {
    left[j] = x - t[mu + 1 - j];
    right[j] = t[mu + j] - x;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[r] / (right[r + 1] + left[j - r]);
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
  return N;
}

// Knot span of x for the clamped knot vector with n coefficients: degree <= mu <= n - 1.
int span_of(const std::vector<double>& t, int n, double x) {
  const auto it = std::upper_bound(t.begin() + degree + 1, t.begin() + n, x);
  return static_cast<int>(it - t.begin()) - 1;
}

struct Spline {
  std::vector<double> breaks;
  std::vector<std::array<double, 6>> taylor;
};

// Interpolating quintic spline through (x_i, y_i), not-a-knot ends, as Taylor coefficients at the
// left end of each polynomial piece.
Spline interpolate_quintic(const std::vector<double>& x, const std::vector<double>& y, const std::string& where) {
  const int n = static_cast<int>(x.size());
  // Knots: x_0 six times, the rows x_3 .. x_{n-4}, x_{n-1} six times (n + 6 knots, n B-splines).
  std::vector<double> t;
  t.reserve(n + degree + 1);
  for (int k = 0; k <= degree; ++k) t.push_back(x.front());
  for (int i = 3; i <= n - 4; ++i) t.push_back(x[i]);
  for (int k = 0; k <= degree; ++k) t.push_back(x.back());

  // Collocation B c = y, band storage A(i, j) = band[i][j - i + 5], |j - i| <= 5.
  constexpr int w = degree;
  std::vector<std::array<double, 2 * w + 1>> band(n);
  std::vector<double> c(y);
  for (int i = 0; i < n; ++i) {
    band[i].fill(0.0);
    const int mu = span_of(t, n, x[i]);
    const auto N = basis(t, mu, degree, x[i]);
    for (int r = 0; r <= degree; ++r) {
      const int j = mu - degree + r;
      if (std::abs(j - i) > w) {
        if (N[r] != 0.0) throw NodeError("file", where + "internal: collocation outside the band");
        continue;
      }
      band[i][j - i + w] = N[r];
    }
  }
  // Gaussian elimination without pivoting (the collocation matrix is totally positive).
  for (int k = 0; k < n; ++k) {
    const double pivot = band[k][w];
    if (!(std::abs(pivot) > 0.0)) throw NodeError("file", where + "the spline through the table is singular");
    for (int i = k + 1; i <= std::min(n - 1, k + w); ++i) {
      const double f = band[i][k - i + w] / pivot;
      if (f == 0.0) continue;
      for (int j = k; j <= std::min(n - 1, k + w); ++j) band[i][j - i + w] -= f * band[k][j - k + w];
      c[i] -= f * c[k];
    }
  }
  for (int k = n - 1; k >= 0; --k) {
    double sum = c[k];
    for (int j = k + 1; j <= std::min(n - 1, k + w); ++j) sum -= band[k][j - k + w] * c[j];
    c[k] = sum / band[k][w];
  }

  // Coefficients of the derivatives: S^(r) = sum_j c^(r)_j B_{j, 5-r}, with
  // c^(r)_j = (6 - r)(c^(r-1)_j - c^(r-1)_{j-1}) / (t_{j+6-r} - t_j), j = r .. n-1.
  std::array<std::vector<double>, degree + 1> d;
  d[0] = c;
  for (int r = 1; r <= degree; ++r) {
    d[r].assign(n, 0.0);
    for (int j = r; j < n; ++j) d[r][j] = (degree + 1 - r) * (d[r - 1][j] - d[r - 1][j - 1]) / (t[j + degree + 1 - r] - t[j]);
  }

  // Taylor coefficients at the left end of every piece [t_mu, t_mu+1], mu = 5 .. n-1.
  Spline out;
  constexpr double factorial[degree + 1] = {1.0, 1.0, 2.0, 6.0, 24.0, 120.0};
  for (int mu = degree; mu <= n - 1; ++mu) {
    const double a = t[mu];
    std::array<double, 6> coef{};
    for (int r = 0; r <= degree; ++r) {
      const int deg = degree - r;
      const auto N = basis(t, mu, deg, a);
      double v = 0.0;
      for (int k = 0; k <= deg; ++k) v += d[r][mu - deg + k] * N[k];
      coef[r] = v / factorial[r];
    }
    out.breaks.push_back(a);
    out.taylor.push_back(coef);
  }
  out.breaks.push_back(t[n]);
  return out;
}

}  // namespace

LiftTable parse_lift_table(std::string_view text, const std::string& source, double angle_scale, double lift_scale) {
  LiftTable table;
  table.source = source;
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

TableLaw::TableLaw(const LiftTable& table, double base_radius) : base_radius_(base_radius) {
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
  std::vector<double> x, y;
  for (std::size_t i = first; i < last; ++i) {
    x.push_back(rows[i].angle);
    y.push_back(rows[i].lift);
  }
  row_angles_ = x;
  Spline s = interpolate_quintic(x, y, src + ": ");
  breaks_ = std::move(s.breaks);
  taylor_ = std::move(s.taylor);
  for (const auto& c : taylor_)
    for (double v : c)
      if (!std::isfinite(v)) throw NodeError("file", src + ": the interpolation of the table overflowed");

  // Maximum of the interpolant, over each polynomial piece.
  long evaluations = 0;
  const auto best = numerics::maximize_piecewise([this](double a) { return at(a).lift; }, breaks_, 12, evaluations);
  max_lift_ = best.value;
  max_lift_angle_ = best.x;
}

LiftDerivatives TableLaw::evaluate_in_event(double phi) const {
  const auto it = std::upper_bound(breaks_.begin(), breaks_.end() - 1, phi);
  const std::size_t i = it == breaks_.begin() ? 0 : static_cast<std::size_t>(it - breaks_.begin()) - 1;
  const double u = phi - breaks_[i];
  const auto& a = taylor_[i];
  // h = sum a_r u^r and its first three derivatives, by Horner.
  const double h = a[0] + u * (a[1] + u * (a[2] + u * (a[3] + u * (a[4] + u * a[5]))));
  const double v = a[1] + u * (2.0 * a[2] + u * (3.0 * a[3] + u * (4.0 * a[4] + u * 5.0 * a[5])));
  const double acc = 2.0 * a[2] + u * (6.0 * a[3] + u * (12.0 * a[4] + u * 20.0 * a[5]));
  const double j = 6.0 * a[3] + u * (24.0 * a[4] + u * 60.0 * a[5]);
  return {h, v, acc, j};
}

CamLawDefinition table_law_definition() {
  CamLawDefinition d;
  d.type = "cam.table";
  d.version = 1;
  d.summary = "tabulated lift from a CSV file (cam angle, lift), quintic spline interpolation; lift and event from the file";
  d.derives_lift_and_action = true;
  d.params = {
      ParamSpec::text("file",
                      "CSV lift table: cam angle, lift; ',' ';' or blank separated, '#' comments, one header line "
                      "allowed; a relative path is taken from the scene file's folder. max_lift and action_angle come "
                      "from it; if given they must agree (0.1 %, 1e-4 deg)")
          .as_path(),
      ParamSpec::choice("angle_origin", {"nose", "start_of_lift"},
                        "where the table's angles are counted from: nose (0 at the top, the lift event around it), or "
                        "start_of_lift (0 where the lift begins; the event is then centred on 0)")
          .with_default("nose"),
      ParamSpec::text("angle_unit", "unit of the table's angle column").with_default(std::string("deg")),
      ParamSpec::text("lift_unit", "unit of the table's lift column").with_default(std::string("mm")),
  };
  d.make = [](const CamBasics& basics, const ParamSet& params, OutputSet&) -> std::shared_ptr<const CamLaw> {
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
    const std::string& path = params.text("file");
    LiftTable table = read_lift_table(path, angle_scale, lift_scale);
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
    auto law = std::make_shared<const TableLaw>(table, basics.base_radius);

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
