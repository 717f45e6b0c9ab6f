#include <mechgraph/domain/tolerance.hpp>

#include <algorithm>
#include <cmath>

namespace mechgraph {

std::string_view to_string(Distribution d) {
  switch (d) {
    case Distribution::normal: return "normal";
    case Distribution::uniform: return "uniform";
    case Distribution::triangular: return "triangular";
  }
  return "?";
}

const std::vector<std::string>& distribution_names() {
  static const std::vector<std::string> names{"normal", "uniform", "triangular"};
  return names;
}

std::optional<Distribution> parse_distribution(std::string_view name) {
  for (Distribution d : {Distribution::normal, Distribution::uniform, Distribution::triangular})
    if (name == to_string(d)) return d;
  return std::nullopt;
}

Distribution distribution_from(std::string_view text, const std::string& parameter, const std::string& context) {
  if (const auto d = parse_distribution(text)) return *d;
  std::string valid;
  for (const std::string& n : distribution_names()) valid += (valid.empty() ? "" : ", ") + n;
  throw NodeError(parameter, (context.empty() ? parameter : context) + ": distribution '" + std::string(text) +
                                 "' is not one of " + valid);
}

ParamSpec distribution_param(std::string name, std::string doc) {
  return ParamSpec::choice(std::move(name), distribution_names(), std::move(doc)).with_default("normal");
}

double standard_deviation(Distribution d, double half_range) {
  switch (d) {
    case Distribution::normal: return half_range / 3.0;
    case Distribution::uniform: return half_range / std::sqrt(3.0);
    case Distribution::triangular: return half_range / std::sqrt(6.0);
  }
  return 0.0;
}

double PlayTerm::mean() const {
  double s = 0.0;
  for (const ToleranceLink& l : links) s += l.sensitivity * l.mean;
  return s;
}

double PlayTerm::lower() const {
  double s = mean();
  for (const ToleranceLink& l : links) s -= std::abs(l.sensitivity) * l.half_range;
  return s;
}

double PlayTerm::upper() const {
  double s = mean();
  for (const ToleranceLink& l : links) s += std::abs(l.sensitivity) * l.half_range;
  return s;
}

double PlayTerm::play_min() const { return std::max(0.0, lower()); }
double PlayTerm::play_max() const { return std::max(0.0, upper()); }

double JointPlay::play_min() const {
  double s = 0.0;
  for (const PlayTerm& t : terms_) s += t.play_min();
  return s;
}

double JointPlay::play_max() const {
  double s = 0.0;
  for (const PlayTerm& t : terms_) s += t.play_max();
  return s;
}

}  // namespace mechgraph
