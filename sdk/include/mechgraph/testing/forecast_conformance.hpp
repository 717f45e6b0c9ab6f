#pragma once
// The forecast-reads check of the node conformance suite: a type that says which parameters its
// forecast reads (ForecastReads, mechgraph.node.forecast_reads/1) must give the same forecast
// whatever the value of every other parameter. A host trusts the list to ask the forecast once for
// all the cases of a sweep, so a parameter read but not listed would let a sweep past its budget.
// Each parameter not listed is set in turn to other values: a number or an integer to the ends of
// its range, its example and default and values near the one given; a choice to each choice; a
// text to its example, its default and the empty text; a list or a record list one element
// shorter and one longer. So that a parameter read only for some value of a listed choice is seen,
// the probes run again with each listed choice set to each of its values.
#include <mechgraph/node.hpp>
#include <mechgraph/testing/report.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace mechgraph::testing {
namespace detail {

// A list one element shorter (when it has one) and one longer (its last element again, or `first`
// for an empty list when there is one to add).
template <class Element>
void length_probes(const ParamValue& given, std::vector<Element> ParamValue::*list, const std::optional<Element>& first,
                   std::vector<ParamValue>& out) {
  const std::vector<Element>& elements = given.*list;
  if (!elements.empty()) {
    ParamValue shorter = given;
    (shorter.*list).pop_back();
    out.push_back(std::move(shorter));
  }
  if (!elements.empty() || first) {
    ParamValue longer = given;
    (longer.*list).push_back(elements.empty() ? *first : elements.back());
    out.push_back(std::move(longer));
  }
}

// The values the check tries for a parameter (`given`: its value in the checked set, of its kind).
inline std::vector<ParamValue> forecast_probe_values(const ParamSpec& spec, const ParamValue& given) {
  std::vector<ParamValue> out;
  switch (spec.kind) {
    case ParamKind::choice:
      for (const std::string& c : spec.choices)
        if (c != given.text) out.push_back(ParamValue::of_choice(c));
      return out;
    case ParamKind::text:
      for (const auto& v : {spec.example_value, spec.default_value, std::optional<ParamValue>(ParamValue::of_text(""))})
        if (v && v->kind == ParamKind::text && v->text != given.text) out.push_back(ParamValue::of_text(v->text));
      return out;
    case ParamKind::number_list: length_probes(given, &ParamValue::numbers, std::optional<double>(1.0), out); return out;
    case ParamKind::record_list: length_probes(given, &ParamValue::records, std::optional<Record>(), out); return out;
    case ParamKind::number:
    case ParamKind::integer: break;
  }
  std::vector<double> candidates{given.number * 2, given.number / 2, given.number + 1, given.number - 1};
  if (std::isfinite(spec.min)) candidates.push_back(spec.min);
  if (std::isfinite(spec.max)) candidates.push_back(spec.max);
  for (const auto& v : {spec.example_value, spec.default_value})
    if (v && (v->kind == ParamKind::number || v->kind == ParamKind::integer)) candidates.push_back(v->number);
  constexpr double long_range = 9.0e18;  // within long on every platform the SDK builds on
  for (double c : candidates) {
    if (spec.kind == ParamKind::integer) c = std::round(std::clamp(c, -long_range, long_range));
    if (!std::isfinite(c) || c == given.number || !spec.admits(c)) continue;
    if (std::any_of(out.begin(), out.end(), [&](const ParamValue& v) { return v.number == c; })) continue;
    out.push_back(spec.kind == ParamKind::integer ? ParamValue::of_integer(static_cast<long>(c)) : ParamValue::of_number(c));
  }
  return out;
}

inline std::string probe_text(const ParamSpec& spec, const ParamValue& v) {
  switch (spec.kind) {
    case ParamKind::choice:
    case ParamKind::text: return "'" + v.text + "'";
    case ParamKind::number_list: return "a list of " + std::to_string(v.numbers.size());
    case ParamKind::record_list: return "a list of " + std::to_string(v.records.size()) + " records";
    default: return std::to_string(v.number);
  }
}

// Equal figures; NaN equals NaN (a forecast may say "no bound" so, whatever the parameter).
inline bool same_figure(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }
inline bool same_forecast(const std::optional<WorkForecast>& a, const std::optional<WorkForecast>& b) {
  if (!a || !b) return !a && !b;
  return same_figure(a->items, b->items) && same_figure(a->memory, b->memory) && same_figure(a->output_size, b->output_size);
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
  } catch (...) {
    r.add(suite, check, false, "forecast_reads() threw something that is not a std::exception");
    return;
  }
  if (!reads) return;
  const NodeInfo& info = type.info();
  for (const std::string& name : *reads)
    if (!info.find_param(name)) {
      r.add(suite, check, false, "names '" + name + "', which is none of its parameters");
      return;
    }
  const auto named = [&](const std::string& name) { return std::find(reads->begin(), reads->end(), name) != reads->end(); };
  // The sets the probes start from: the one given, and one for each other value of each named choice.
  std::vector<std::pair<std::string, ParamSet>> starts{{"", params}};
  for (const ParamSpec& spec : info.params) {
    if (spec.kind != ParamKind::choice || !named(spec.name)) continue;
    const auto given = params.all().find(spec.name);
    for (const std::string& c : spec.choices) {
      if (given != params.all().end() && given->second.text == c) continue;
      ParamSet start = params;
      start.set(spec.name, ParamValue::of_choice(c));
      starts.emplace_back(" (with " + spec.name + " '" + c + "')", std::move(start));
    }
  }
  std::size_t probed = 0, values = 0;
  std::vector<std::string> unprobed;
  for (const auto& [with, start] : starts) {
    std::string thrown;
    const std::optional<WorkForecast> base = detail::forecast_or_none(type, start, sizes, thrown);
    if (!thrown.empty()) {
      r.add(suite, check, false, "the forecast threw" + with + ": " + thrown);
      return;
    }
    for (const ParamSpec& spec : info.params) {
      if (named(spec.name)) continue;
      const auto given = start.all().find(spec.name);
      ParamValue current = given != start.all().end() ? given->second : ParamValue{};
      current.kind = spec.kind;
      const std::vector<ParamValue> probes = detail::forecast_probe_values(spec, current);
      if (probes.empty()) {
        if (with.empty()) unprobed.push_back(spec.name);
        continue;
      }
      if (with.empty()) ++probed;
      for (const ParamValue& v : probes) {
        ParamSet changed = start;
        changed.set(spec.name, v);
        ++values;
        const std::optional<WorkForecast> other = detail::forecast_or_none(type, changed, sizes, thrown);
        if (!thrown.empty() || !detail::same_forecast(base, other)) {
          r.add(suite, check, false,
                "'" + spec.name + "' is not named, but setting it to " + detail::probe_text(spec, v) + with + " " +
                    (thrown.empty() ? "changes the forecast" : "makes the forecast throw: " + thrown));
          return;
        }
      }
    }
  }
  std::string detail_text = std::to_string(probed) + " parameters not named probed with " + std::to_string(values) +
                            " values from " + std::to_string(starts.size()) + " starting sets: the same forecast";
  if (!unprobed.empty()) {
    detail_text += "; not probed (no other value to try):";
    for (const std::string& name : unprobed) detail_text += " " + name;
  }
  r.add(suite, check, true, detail_text);
}

}  // namespace mechgraph::testing
