#include <mechgraph/did_you_mean.hpp>

#include <algorithm>
#include <numeric>

namespace mechgraph {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), 0);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string closest_match(std::string_view name, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, name.size() / 3) + 1;
  for (const std::string& c : candidates) {
    const std::size_t d = edit_distance(name, c);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  return best;
}

std::string unknown_name_message(std::string_view what, std::string_view name,
                                 const std::vector<std::string>& candidates) {
  std::string msg = "unknown " + std::string(what) + " '" + std::string(name) + "'";
  const std::string best = closest_match(name, candidates);
  if (!best.empty()) msg += "; did you mean '" + best + "'?";
  std::vector<std::string> sorted = candidates;
  std::sort(sorted.begin(), sorted.end());
  const std::string plural = std::string(what) + (what.ends_with("s") ? "es" : "s");  // classes, units
  msg += sorted.empty() ? std::string("; there are none") : "; valid " + plural + " are: (";
  for (std::size_t i = 0; i < sorted.size(); ++i) msg += (i ? " " : "") + sorted[i];
  if (!sorted.empty()) msg += ")";
  return msg;
}

}  // namespace mechgraph
