#include "table_cost.hpp"

#include "smoothing_spline.hpp"
#include "table_law.hpp"

#include <mechgraph/bounded_read.hpp>

#include <algorithm>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <tuple>

namespace mechgraph::cams {
namespace {

// Work items (about a microsecond each) and bytes per row, measured on 260 to 26000-row tables
// (the calibration test keeps them honest).
constexpr double read_items_per_row = 5.0;         // parse, check, trim
constexpr double interpolate_items_per_row = 4.0;  // one quintic interpolant (banded solve, pieces)
constexpr double solve_items_per_row = 2.0;        // one penalised least-squares solve with its dof
constexpr double bytes_per_row_read = 200.0;       // rows, law pieces, noise pieces
constexpr double bytes_per_row_smoothed = 1000.0;  // the smoother's bands, one solve's factor and inverse band

// The line count of a file, kept by its path, size and time of change.
double counted_lines(const std::string& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return 0.0;
  const auto changed = std::filesystem::last_write_time(path, ec);
  if (ec) return 0.0;
  using Key = std::tuple<std::string, std::uintmax_t, std::filesystem::file_time_type>;
  static std::mutex guard;
  static std::map<Key, double> counts;
  const Key key{path, size, changed};
  {
    const std::lock_guard<std::mutex> lock(guard);
    if (const auto it = counts.find(key); it != counts.end()) return it->second;
  }
  std::string text;
  try {
    text = read_bounded_file(path, lift_table_limit);
  } catch (const std::exception&) {
    return 0.0;  // evaluate() reads it again and says why it cannot
  }
  const double lines = static_cast<double>(std::count(text.begin(), text.end(), '\n')) + 1.0;
  const std::lock_guard<std::mutex> lock(guard);
  if (counts.size() >= 64) counts.clear();
  counts.emplace(key, lines);
  return lines;
}

}  // namespace

double table_rows(const ParamSet& params) {
  if (params.has("angles")) return static_cast<double>(params.numbers("angles").size());
  if (params.has("file")) return counted_lines(params.text("file"));
  return 0.0;
}

CamLawCost table_cost(const ParamSet& params) {
  const double rows = std::max(table_rows(params), 1.0);
  const std::string method = params.has("smoothing") ? params.text("smoothing") : std::string("none");
  const double solves = method == "none" ? 0.0 : QuinticSmoother::most_solves(method == "gcv", rows);
  CamLawCost cost;
  cost.pieces = rows;
  cost.search_factor = table_pieces_per_row;
  cost.items = rows * (read_items_per_row + 2.0 * interpolate_items_per_row + solves * solve_items_per_row);
  cost.memory = rows * (method == "none" ? bytes_per_row_read : bytes_per_row_read + bytes_per_row_smoothed);
  const std::string source = params.has("angles") ? "angles" : "file";
  cost.driver = source + " (about " + std::to_string(static_cast<long>(rows)) + " rows, smoothing " + method +
                (solves > 0 ? ", at most " + std::to_string(static_cast<long>(solves)) + " solves" : std::string()) + ")";
  return cost;
}

}  // namespace mechgraph::cams
