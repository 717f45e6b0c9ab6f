#include <mechgraph/uncertainty/study_spec.hpp>

#include <mechgraph/bounded_read.hpp>
#include <mechgraph/did_you_mean.hpp>
#include <mechgraph/error_subject.hpp>
#include <mechgraph/sweep/case_table.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/number_prefix.hpp>
#include <mechgraph/text_escape.hpp>
#include <mechgraph/units.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

namespace mechgraph {

std::string to_string(SamplingMethod m) {
  switch (m) {
    case SamplingMethod::monte_carlo: return "monte_carlo";
    case SamplingMethod::latin_hypercube: return "latin_hypercube";
    case SamplingMethod::sobol: return "sobol";
  }
  return "?";
}

std::size_t StudySpec::evaluations() const { return sensitivity ? samples * (parameters.size() + 2) : samples; }

namespace {

[[noreturn]] void fail(const SourceLocation& where, const std::string& message) { throw_scene_error_at(where, message); }

const RawValue& expect_map(const RawValue& v, const std::string& what) {
  if (v.kind != RawValue::Kind::map) fail(v.where, "expected " + what + " as a map (key: value)");
  return v;
}

std::string scalar(const RawValue& v, const std::string& what) {
  if (v.kind != RawValue::Kind::scalar) fail(v.where, "expected " + what + " (a single value)");
  return v.text;
}

void check_keys(const RawValue& map, const std::vector<std::string>& valid, const std::string& what) {
  for (const auto& [key, value] : map.fields)
    if (std::find(valid.begin(), valid.end(), key) == valid.end()) fail(value.key_where, unknown_name_message(what, key, valid));
}

const RawValue* field(const RawValue& map, std::string_view key) {
  for (const auto& [k, v] : map.fields)
    if (k == key) return &v;
  return nullptr;
}

// A number with its unit, finite. `unit` receives the unit as written ("" for none).
Quantity quantity(const RawValue& v, const std::string& what, std::string* unit = nullptr) {
  const std::string text = scalar(v, what);
  Quantity q;
  try {
    q = parse_quantity(text);
  } catch (const UnitError& e) {
    fail(v.where, what + ": " + quoted_text_excerpt(text) + ": " + e.what());
  }
  if (!std::isfinite(q.value)) fail(v.where, what + ": " + quoted_text_excerpt(text) + " is not a finite number");
  if (unit) {
    *unit = std::string(unit_after_number(text));
  }
  return q;
}

double plain_number(const RawValue& v, const std::string& what) {
  const Quantity q = quantity(v, what);
  if (!q.dimension.dimensionless()) fail(v.where, what + " is a plain number, found " + q.dimension.describe());
  return q.value;
}

std::size_t whole(const RawValue& v, const std::string& what, std::size_t low, std::size_t high) {
  const std::string text = scalar(v, what);
  std::size_t n = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (ec != std::errc() || ptr != text.data() + text.size() || n < low || n > high)
    fail(v.where, what + ": " + quoted_text_excerpt(text) + " is not a whole number from " + std::to_string(low) + " to " +
                      std::to_string(high));
  return n;
}

bool boolean(const RawValue& v, const std::string& what) {
  const std::string text = scalar(v, what);
  if (text == "true" || text == "yes") return true;
  if (text == "false" || text == "no") return false;
  fail(v.where, what + ": expected true or false, found " + quoted_text_excerpt(text));
}

// The numbers of one distribution share a dimension: the first one written sets it.
struct DimensionCheck {
  std::optional<Dimension> dimension;
  std::string unit;
  double take(const RawValue& v, const std::string& what) {
    std::string written_unit;
    const Quantity q = quantity(v, what, &written_unit);
    if (dimension && !(q.dimension == *dimension))
      fail(v.where, what + " is " + q.dimension.describe() + " where the distribution's other values are " + dimension->describe());
    if (!dimension) dimension = q.dimension;
    if (unit.empty()) unit = written_unit;
    last_unit = written_unit;
    return q.value;
  }
  // A width (a sigma, a tolerance) is a difference of two values, which a unit's offset does not
  // shift: a spread of 5 degC is 5 K, not 278.15 K. The scale alone: the value less what zero of
  // its unit is in SI.
  double take_width(const RawValue& v, const std::string& what) {
    const double value = take(v, what);
    return last_unit.empty() ? value : value - parse_quantity("0 " + last_unit).value;
  }
  std::string last_unit;  // the unit of the value taken last, as written
};

void read_normal(const RawValue& body, Marginal& m, DimensionCheck& dims) {
  expect_map(body, "normal's values");
  check_keys(body, {"mean", "sigma", "nominal", "tolerance", "lower", "upper", "cp"}, "normal key");
  const RawValue *mean = field(body, "mean"), *sigma = field(body, "sigma"), *nominal = field(body, "nominal"),
                 *tolerance = field(body, "tolerance"), *lower = field(body, "lower"), *upper = field(body, "upper"),
                 *cp = field(body, "cp");
  double process_capability = 1.0;
  if (cp) {
    process_capability = plain_number(*cp, "cp");
    if (!(process_capability > 0)) fail(cp->where, "cp must be greater than 0");
  }
  m.kind = Marginal::Kind::normal;
  if (mean && sigma && !nominal && !tolerance && !lower && !upper && !cp) {
    m.a = dims.take(*mean, "mean");
    m.b = dims.take_width(*sigma, "sigma");
    if (!(m.b > 0)) fail(sigma->where, "sigma must be greater than 0");
  } else if (nominal && tolerance && !mean && !sigma && !lower && !upper) {
    // nominal +- tolerance is the specification; Cp = (USL - LSL) / (6 sigma) = 2 t / (6 sigma).
    m.a = dims.take(*nominal, "nominal");
    const double t = dims.take_width(*tolerance, "tolerance");
    if (!(t > 0)) fail(tolerance->where, "tolerance (the half width, nominal +- tolerance) must be greater than 0");
    m.b = t / (3.0 * process_capability);
  } else if (lower && upper && !mean && !sigma && !nominal && !tolerance) {
    const double lo = dims.take(*lower, "lower"), hi = dims.take(*upper, "upper");
    if (!(hi > lo)) fail(upper->where, "upper must be greater than lower");
    if (!std::isfinite(hi - lo)) fail(upper->where, "upper - lower is beyond the range of a double");
    m.a = lo + 0.5 * (hi - lo);  // the middle, without overflowing at the ends of the doubles
    m.b = (hi - lo) / (6.0 * process_capability);
  } else {
    fail(body.where, "a normal distribution is { mean, sigma }, { nominal, tolerance[, cp] } or { lower, upper[, cp] } "
                     "(spec limits with the process capability Cp, default 1)");
  }
  if (!(m.b > 0)) fail(body.where, "sigma must be greater than 0");
  // The draws reach about 8.3 sigma either side (the quantile at 2^-53): they must stay doubles.
  if (!std::isfinite(std::abs(m.a) + 9.0 * m.b))
    fail(body.where, "mean +- 9 sigma is beyond the range of a double: the draws would overflow");
  // Nor may the spread vanish in the mean's rounding: every draw would be the mean itself.
  if (m.a + 9.0 * m.b == m.a && m.a - 9.0 * m.b == m.a)
    fail(body.where, "sigma is below the spacing of doubles at the mean: every draw would be the mean itself");
}

void read_uniform(const RawValue& body, Marginal& m, DimensionCheck& dims) {
  expect_map(body, "uniform's values");
  check_keys(body, {"lower", "upper"}, "uniform key");
  const RawValue *lower = field(body, "lower"), *upper = field(body, "upper");
  if (!lower || !upper) fail(body.where, "a uniform distribution is { lower, upper }");
  m.kind = Marginal::Kind::uniform;
  m.a = dims.take(*lower, "lower");
  m.b = dims.take(*upper, "upper");
  if (!(m.b > m.a)) fail(upper->where, "upper must be greater than lower");
  if (!std::isfinite(m.b - m.a)) fail(upper->where, "upper - lower is beyond the range of a double");
}

void read_triangular(const RawValue& body, Marginal& m, DimensionCheck& dims) {
  expect_map(body, "triangular's values");
  check_keys(body, {"lower", "mode", "upper"}, "triangular key");
  const RawValue *lower = field(body, "lower"), *mode = field(body, "mode"), *upper = field(body, "upper");
  if (!lower || !upper) fail(body.where, "a triangular distribution is { lower, mode, upper } (mode: default the middle)");
  m.kind = Marginal::Kind::triangular;
  m.a = dims.take(*lower, "lower");
  m.b = dims.take(*upper, "upper");
  if (!(m.b > m.a)) fail(upper->where, "upper must be greater than lower");
  if (!std::isfinite(m.b - m.a)) fail(upper->where, "upper - lower is beyond the range of a double");
  m.c = mode ? dims.take(*mode, "mode") : m.a + 0.5 * (m.b - m.a);  // default: the middle (no overflow)
  if (!(m.c >= m.a && m.c <= m.b)) fail((mode ? mode : &body)->where, "the mode must lie between lower and upper");
}

void read_iso286(const RawValue& body, Marginal& m, DimensionCheck& dims, const Iso286Limits& iso286) {
  expect_map(body, "iso286's values");
  check_keys(body, {"size", "class", "distribution", "cp"}, "iso286 key");
  const RawValue *size = field(body, "size"), *cls = field(body, "class"), *dist = field(body, "distribution"), *cp = field(body, "cp");
  if (!size || !cls) fail(body.where, "an ISO 286 size is { size: 20 mm, class: H7 } (distribution: normal or uniform, cp)");
  const double nominal = dims.take(*size, "size");
  if (!(*dims.dimension == dim::length)) fail(size->where, "size is a length, found " + dims.dimension->describe());
  const std::string tolerance_class = scalar(*cls, "a tolerance class");
  if (!iso286) fail(cls->where, "ISO 286 limits need the fits plugin (fit.iso286), which is not loaded");
  std::pair<double, double> deviation;
  try {
    deviation = iso286(nominal, tolerance_class);
  } catch (const std::exception& e) {
    fail(cls->where, "ISO 286 class " + quoted_text_excerpt(tolerance_class) + " at " + scalar(*size, "size") + ": " + e.what());
  }
  const double lo = nominal + deviation.first, hi = nominal + deviation.second;
  const std::string shape = dist ? scalar(*dist, "a distribution") : "normal";
  if (shape == "uniform") {
    if (cp) fail(cp->where, "cp belongs to a normal spread over the zone, not to a uniform one");
    m.kind = Marginal::Kind::uniform;
    m.a = lo;
    m.b = hi;
  } else if (shape == "normal") {
    const double process_capability = cp ? plain_number(*cp, "cp") : 1.0;
    if (!(process_capability > 0)) fail(cp->where, "cp must be greater than 0");
    m.kind = Marginal::Kind::normal;
    m.a = 0.5 * (lo + hi);
    m.b = (hi - lo) / (6.0 * process_capability);
  } else {
    fail(dist->where, unknown_name_message("ISO 286 distribution", shape, {"normal", "uniform"}));
  }
  if (!(m.b > (m.kind == Marginal::Kind::uniform ? m.a : 0.0))) fail(cls->where, "the tolerance zone is empty");
}

std::string written_text(const RawValue& v) {
  if (v.kind == RawValue::Kind::scalar) return v.text;
  std::string out = v.kind == RawValue::Kind::list ? "[" : "{";
  bool first = true;
  if (v.kind == RawValue::Kind::list)
    for (const RawValue& item : v.items) out += (first ? "" : ", ") + written_text(item), first = false;
  else
    for (const auto& [k, f] : v.fields) out += (first ? "" : ", ") + k + ": " + written_text(f), first = false;
  return out + (v.kind == RawValue::Kind::list ? "]" : "}");
}

}  // namespace

UncertainParameter parse_uncertain_parameter(const std::string& name, const RawValue& value, const Iso286Limits& iso286) {
  UncertainParameter p;
  p.name = name;
  p.where = value.key_where.line ? value.key_where : value.where;
  p.written = written_text(value);
  expect_map(value, "the distribution of '" + name + "'");
  check_keys(value, {"normal", "uniform", "triangular", "iso286", "truncate"}, "distribution");
  DimensionCheck dims;
  int shapes = 0;
  for (const auto& [key, body] : value.fields) {
    if (key == "truncate") continue;
    ++shapes;
    if (key == "normal") read_normal(body, p.marginal, dims);
    if (key == "uniform") read_uniform(body, p.marginal, dims);
    if (key == "triangular") read_triangular(body, p.marginal, dims);
    if (key == "iso286") read_iso286(body, p.marginal, dims, iso286);
  }
  if (shapes != 1) fail(value.where, "'" + name + "' needs one distribution: normal, uniform, triangular or iso286");
  if (const RawValue* t = field(value, "truncate")) {
    expect_map(*t, "truncate");
    check_keys(*t, {"lower", "upper"}, "truncate key");
    if (const RawValue* lo = field(*t, "lower")) p.marginal.lower = dims.take(*lo, "truncate lower");
    if (const RawValue* hi = field(*t, "upper")) p.marginal.upper = dims.take(*hi, "truncate upper");
    if (!p.marginal.lower && !p.marginal.upper) fail(t->where, "truncate needs lower, upper or both");
    if (p.marginal.lower && p.marginal.upper && !(*p.marginal.upper > *p.marginal.lower))
      fail(t->where, "truncate: upper must be greater than lower");
    // The truncated distribution must keep some probability (no empty or vanishing interval); far
    // in a tail is allowed (sampled there on the tail's own probabilities, distribution.cpp).
    if (!(p.marginal.kept_probability() > 0.0))
      fail(t->where, "truncate keeps no probability of the distribution (none a double can hold: the interval lies too far in a "
                     "tail or is too narrow)");
  }
  p.marginal.dimension = dims.dimension.value_or(Dimension{});
  p.unit = dims.unit;
  return p;
}

StudySpec parse_study(const RawValue& block, const Iso286Limits& iso286) {
  StudySpec spec;
  expect_map(block, "uncertainty");
  check_keys(block, {"method", "samples", "seed", "sensitivity", "bootstrap", "confidence", "quantiles", "bins", "parameters",
                     "correlations", "limits", "events"},
             "uncertainty key");
  if (const RawValue* m = field(block, "method")) {
    const std::string name = scalar(*m, "a sampling method");
    if (name == "monte_carlo") spec.method = SamplingMethod::monte_carlo;
    else if (name == "latin_hypercube") spec.method = SamplingMethod::latin_hypercube;
    else if (name == "sobol") spec.method = SamplingMethod::sobol;
    else fail(m->where, unknown_name_message("sampling method", name, {"monte_carlo", "latin_hypercube", "sobol"}));
  }
  if (const RawValue* n = field(block, "samples")) spec.samples = whole(*n, "samples", 2, max_sweep_cases);
  if (const RawValue* s = field(block, "seed")) spec.seed = whole(*s, "seed", 0, std::size_t{1} << 62);
  if (const RawValue* s = field(block, "sensitivity")) spec.sensitivity = boolean(*s, "sensitivity");
  if (const RawValue* b = field(block, "bootstrap")) spec.bootstrap = whole(*b, "bootstrap", 0, 10000);
  if (const RawValue* c = field(block, "confidence")) {
    spec.confidence = plain_number(*c, "confidence");
    if (!(spec.confidence > 0 && spec.confidence < 1)) fail(c->where, "confidence is a level between 0 and 1, e.g. 0.95");
  }
  if (const RawValue* b = field(block, "bins")) spec.bins = whole(*b, "bins", 1, 10000);
  if (const RawValue* q = field(block, "quantiles")) {
    if (q->kind != RawValue::Kind::list) fail(q->where, "expected quantiles as a list of levels, e.g. [0.01, 0.5, 0.99]");
    spec.quantiles.clear();
    for (const RawValue& item : q->items) {
      const double p = plain_number(item, "a quantile level");
      if (!(p > 0 && p < 1)) fail(item.where, "a quantile level lies between 0 and 1");
      if (std::find(spec.quantiles.begin(), spec.quantiles.end(), p) != spec.quantiles.end())
        fail(item.where, "the quantile level " + item.text + " is given twice");
      spec.quantiles.push_back(p);
    }
  }
  const RawValue* params = field(block, "parameters");
  if (!params || params->fields.empty()) fail(block.where, "uncertainty has no 'parameters' (name: { normal: { mean, sigma } }, ...)");
  expect_map(*params, "parameters");
  if (params->fields.size() > max_study_parameters)
    fail(params->where, "more than " + std::to_string(max_study_parameters) + " uncertain parameters");
  for (const auto& [name, value] : params->fields) spec.parameters.push_back(parse_uncertain_parameter(name, value, iso286));
  if (spec.evaluations() > max_sweep_cases)
    fail(block.where, std::to_string(spec.samples) + " samples need " + std::to_string(spec.evaluations()) + " evaluations, more than the " +
                          std::string(max_sweep_cases_text) + " cases of one study");
  const auto index_of = [&](const RawValue& v) {
    const std::string name = scalar(v, "a parameter name");
    std::vector<std::string> names;
    for (std::size_t i = 0; i < spec.parameters.size(); ++i) {
      if (spec.parameters[i].name == name) return i;
      names.push_back(spec.parameters[i].name);
    }
    fail(v.where, unknown_name_message("uncertain parameter", name, names));
  };
  if (const RawValue* c = field(block, "correlations")) {
    if (c->kind != RawValue::Kind::list) fail(c->where, "expected correlations as a list of [name, name, rho]");
    for (const RawValue& item : c->items) {
      if (item.kind != RawValue::Kind::list || item.items.size() != 3) fail(item.where, "a correlation is [name, name, rho]");
      ParameterCorrelation r{index_of(item.items[0]), index_of(item.items[1]), plain_number(item.items[2], "rho"), item.where};
      if (r.first == r.second) fail(item.where, "a parameter is not correlated with itself");
      if (!(r.rho > -1 && r.rho < 1)) fail(item.items[2].where, "rho lies strictly between -1 and 1");
      for (const ParameterCorrelation& o : spec.correlations)
        if ((o.first == r.first && o.second == r.second) || (o.first == r.second && o.second == r.first))
          fail(item.where, "this pair's correlation is given twice");
      spec.correlations.push_back(r);
    }
    if (spec.sensitivity && !spec.correlations.empty())
      fail(c->where, "Sobol' indices assume independent parameters; drop the correlations or sensitivity: true");
  }
  if (const RawValue* l = field(block, "limits")) {
    expect_map(*l, "limits");
    for (const auto& [output, body] : l->fields) {
      expect_map(body, "the limits of '" + output + "'");
      check_keys(body, {"lower", "upper"}, "limits key");
      SpecLimits s{output, {}, {}, {}, body.key_where};
      parse_port_ref(output, body.key_where);
      DimensionCheck dims;
      if (const RawValue* lo = field(body, "lower")) s.lower = dims.take(*lo, "lower"), s.lower_bare = dims.last_unit.empty();
      if (const RawValue* hi = field(body, "upper")) s.upper = dims.take(*hi, "upper"), s.upper_bare = dims.last_unit.empty();
      if (!s.lower && !s.upper) fail(body.where, "limits need lower, upper or both");
      s.dimension = dims.dimension.value_or(Dimension{});
      if (s.lower && s.upper && !(*s.upper > *s.lower)) fail(body.where, "upper must be greater than lower");
      spec.limits.push_back(std::move(s));
    }
  }
  if (const RawValue* e = field(block, "events")) {
    expect_map(*e, "events");
    for (const auto& [name, body] : e->fields) {
      if (const std::string why = name_problem(name); !why.empty()) fail(body.key_where, "event name " + why);
      expect_map(body, "event '" + name + "'");
      check_keys(body, {"output", "above", "below", "failure"}, "event key");
      StudyEvent ev;
      ev.name = name;
      ev.where = body.key_where;
      const RawValue *output = field(body, "output"), *above = field(body, "above"), *below = field(body, "below"),
                     *failure = field(body, "failure");
      if (failure && !output && !above && !below) {
        ev.kind = StudyEvent::Kind::failure;
        const std::string cls = scalar(*failure, "a failure class");
        if (cls == "any") ev.failure = StudyEvent::Failure::any;
        else if (cls == "scene") ev.failure = StudyEvent::Failure::scene;
        else if (cls == "evaluation") ev.failure = StudyEvent::Failure::evaluation;
        else fail(failure->where, unknown_name_message("failure class", cls, {"any", "scene", "evaluation"}));
      } else if (output && !failure && (above != nullptr) != (below != nullptr)) {
        ev.output = scalar(*output, "node.port");
        parse_port_ref(ev.output, output->where);
        ev.kind = above ? StudyEvent::Kind::above : StudyEvent::Kind::below;
        std::string written_unit;
        const Quantity threshold = quantity(above ? *above : *below, above ? "above" : "below", &written_unit);
        ev.threshold = threshold.value;
        ev.dimension = threshold.dimension;
        ev.bare = written_unit.empty();
      } else {
        fail(body.where, "an event is { output: node.port, above: VALUE } (or below), or { failure: any | scene | evaluation }");
      }
      spec.events.push_back(std::move(ev));
    }
  }
  return spec;
}

}  // namespace mechgraph
