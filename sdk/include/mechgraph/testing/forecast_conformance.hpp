#pragma once
// The forecast-reads check of the node conformance suite: a type that says which parameters its
// forecast reads (ForecastReads, mechgraph.node.forecast_reads/1) must give the same forecast
// whatever the value of every other parameter. A host trusts the list to ask the forecast once for
// all the cases of a sweep, so a parameter read but not listed would let a sweep past its budget.
// Each number, integer and choice parameter not listed is set in turn to the ends of its range, its
// example and default, and values near the one given (every choice for a choice), where admitted.
#include <mechgraph/node.hpp>
#include <mechgraph/testing/report.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace mechgraph::testing {
namespace detail {

// The values the check tries for a parameter (`given`: its value in the checked set).
inline std::vector<ParamValue> forecast_probe_values(const ParamSpec& spec, const ParamValue& given) {
  std::vector<ParamValue> out;
  if (spec.kind == ParamKind::choice) {
    for (const std::string& c : spec.choices) out.push_back(ParamValue::of_choice(c));
    return out;
  }
  if (spec.kind != ParamKind::number && spec.kind != ParamKind::integer) return out;
  std::vector<double> candidates{given.number * 2, given.number / 2, given.number + 1, given.number - 1};
  if (std::isfinite(spec.min)) candidates.push_back(spec.min);
  if (std::isfinite(spec.max)) candidates.push_back(spec.max);
  for (const auto& v : {spec.example_value, spec.default_value})
    if (v && (v->kind == ParamKind::number || v->kind == ParamKind::integer)) candidates.push_back(v->number);
  for (double c : candidates) {
    if (spec.kind == ParamKind::integer) c = std::round(c);
    if (!std::isfinite(c) || c == given.number || !spec.admits(c)) continue;
    if (std::any_of(out.begin(), out.end(), [&](const ParamValue& v) { return v.number == c; })) continue;
    out.push_back(spec.kind == ParamKind::integer ? ParamValue::of_integer(static_cast<long>(c)) : ParamValue::of_number(c));
  }
  return out;
}

inline bool same_forecast(const std::optional<WorkForecast>& a, const std::optional<WorkForecast>& b) {
  if (!a || !b) return !a && !b;
  return a->items == b->items && a->memory == b->memory && a->output_size == b->output_size;
}

inline std::optional<WorkForecast> forecast_or_none(const NodeType& type, const ParamSet& params, const InputSizes& sizes,
                                                    std::string& thrown) {
  try {
    return type.forecast(params, sizes);
  } catch (const std::exception& e) {
    thrown = e.what();
  } catch (...) {
    thrown = "a non-standard exception";
  }
  return std::nullopt;
}

}  // namespace detail

/// Adds the check to `r` when `type` says what its forecast reads; `params` is a checked set (the
/// defaults and the values the author gave), `sizes` the input sizes to ask with.
inline void check_forecast_reads(const NodeType& type, const ParamSet& params, const InputSizes& sizes, Report& r,
                                 const std::string& suite) {
  const auto* declared = dynamic_cast<const ForecastReads*>(&type);
  if (!declared) return;
  const std::string check = "its forecast reads only the parameters it names";
  std::optional<std::vector<std::string>> reads;
  try {
    reads = declared->forecast_reads();
  } catch (const std::exception& e) {
    r.add(suite, check, false, std::string("forecast_reads() threw: ") + e.what());
    return;
  }
  if (!reads) return;
  const NodeInfo& info = type.info();
  for (const std::string& name : *reads)
    if (!info.find_param(name)) {
      r.add(suite, check, false, "names '" + name + "', which is none of its parameters");
      return;
    }
  std::string thrown;
  const std::optional<WorkForecast> base = detail::forecast_or_none(type, params, sizes, thrown);
  if (!thrown.empty()) {
    r.add(suite, check, false, "the forecast threw: " + thrown);
    return;
  }
  std::size_t probed = 0, values = 0;
  for (const ParamSpec& spec : info.params) {
    if (std::find(reads->begin(), reads->end(), spec.name) != reads->end()) continue;
    const auto given = params.all().find(spec.name);
    const ParamValue current = given != params.all().end() ? given->second : ParamValue{spec.kind, 0.0, {}, {}, {}};
    const std::vector<ParamValue> probes = detail::forecast_probe_values(spec, current);
    if (probes.empty()) continue;
    ++probed;
    for (const ParamValue& v : probes) {
      ParamSet changed = params;
      changed.set(spec.name, v);
      ++values;
      const std::optional<WorkForecast> other = detail::forecast_or_none(type, changed, sizes, thrown);
      if (!thrown.empty() || !detail::same_forecast(base, other)) {
        const std::string value = spec.kind == ParamKind::choice ? v.text : std::to_string(v.number);
        r.add(suite, check, false,
              "'" + spec.name + "' is not named, but setting it to " + value + " " +
                  (thrown.empty() ? "changes the forecast" : "makes the forecast throw: " + thrown));
        return;
      }
    }
  }
  r.add(suite, check, true,
        std::to_string(probed) + " parameters not named, " + std::to_string(values) + " values: the same forecast");
}

}  // namespace mechgraph::testing
