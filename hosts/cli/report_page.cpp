#include "report_page.hpp"

#include "declared_port.hpp"
#include "result_files.hpp"
#include "gnuplot_data.hpp"
#include "output_file.hpp"
#include "results_folder.hpp"
#include "spawn.hpp"

#include <mechgraph/csv.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/bounded_read.hpp>
#include <mechgraph/text_escape.hpp>
#include <mechgraph/shown_number.hpp>
#include <mechgraph/units.hpp>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

#ifndef MECHGRAPH_VERSION
#define MECHGRAPH_VERSION "0"
#endif

namespace mechgraph::cli {
namespace {

// Tables with at most this many rows are shown as tables, not plotted (a list of events).
constexpr std::size_t table_rows_shown = 12;
// A channel compared across more nodes than this is drawn as small multiples (a panel per node):
// more curves in one plot hide one another.
constexpr std::size_t overlaid_at_most = 3;

std::string file_safe(std::string text) {
  for (char& c : text)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_')) c = '_';
  return text;
}

// A port or undeclared channel name as a reader says it: "max_force" -> "max force" (declared
// channels say it with their label: DeclaredPort::label).
std::string spoken(std::string name) {
  std::replace(name.begin(), name.end(), '_', ' ');
  return name;
}

// A plot's axis title for a dimension: the quantity's name where it has one ("force", not
// "mass*length/time^2"), else the dimension in base quantities.
std::string quantity(const Dimension& d) {
  static const std::pair<Dimension, const char*> named[] = {
      {dim::force, "force"},           {dim::stress, "stress"},
      {dim::velocity, "velocity"},     {dim::acceleration, "acceleration"},
      {dim::stiffness, "stiffness"},   {dim::length / dim::time.pow(3), "jerk"},
      {dim::frequency, "frequency"},   {dim::angular_speed, "angular speed"},
      {dim::force * dim::length, "moment"}, {dim::length, "length"}, {dim::angle, "angle"}};
  for (const auto& [known, name] : named)
    if (known == d) return name;
  return d.describe();
}

// The unit a value of dimension `d` is shown in: the scene's `units:`, else the port's or
// channel's own, else degrees for an angle and millimetres for a length; "" keeps SI.
std::string display_unit(const Dimension& d, const std::string& own_unit, const DisplayUnits& units) {
  std::string unit = units.unit_for(d, own_unit);
  if (unit.empty() && d == dim::angle) unit = "deg";
  if (unit.empty() && d == dim::length) unit = "mm";
  return unit;
}


// A column to plot: values converted to the unit shown.
struct Column {
  std::string name;   // CSV header: "first height [mm]"
  std::string unit;
  std::vector<double> values;
  std::vector<std::size_t> pieces_from;  // rows (ascending) where a new piece starts: no line from the row before
};

// `title` is what the reader calls it (a label), `frame_tag` the tag of its angle frame when it is
// an angle or a rate per angle of a declared frame (column_tag), else "".
Column shown(const std::string& title, const Dimension& d, const std::vector<double>& si, const std::string& own_unit,
             const DisplayUnits& units, const std::string& frame_tag = {}) {
  Column c;
  c.unit = display_unit(d, own_unit, units);
  const bool convert = !c.unit.empty();
  if (c.unit.empty()) c.unit = d.si_unit() == "1" ? std::string() : d.si_unit();
  c.values.reserve(si.size());
  for (double v : si) c.values.push_back(convert ? to_unit(v, d, c.unit) : v);
  c.unit = unit_with_reference(c.unit, frame_tag);
  c.name = spoken(title) + (c.unit.empty() ? std::string() : " [" + c.unit + "]");
  return c;
}

// Curvature 1/rho in 1/mm from a radius of curvature (in m): an inflection (rho -> +-infinity) is a
// zero crossing instead of a spike, so the plot keeps the scale of the sharp places that matter.
// Points where rho is zero (a cusp, which no node should leave) are left out.
std::pair<Column, Column> curvature_of(const Column& x, const std::vector<double>& radius_si, const std::string& title) {
  std::pair<Column, Column> out;
  out.first.name = x.name;
  out.first.unit = x.unit;
  out.second.name = spoken(title) + " [1/mm]";
  out.second.unit = "1/mm";
  for (std::size_t i = 0; i < std::min(x.values.size(), radius_si.size()); ++i) {
    const double rho_mm = radius_si[i] * 1e3;
    if (!(std::abs(rho_mm) > 1e-12) || !std::isfinite(rho_mm)) continue;
    out.first.values.push_back(x.values[i]);
    out.second.values.push_back(1.0 / rho_mm);
  }
  return out;
}


struct Figure {
  enum class Kind { lines, bars, to_scale, histogram, panel } kind = Kind::lines;
  std::string name;  // file stem
  std::string title, xlabel, ylabel;
  std::vector<std::pair<Column, Column>> curves;  // (x, y) per curve; bars: x unused, labels below
  std::vector<std::string> curve_titles;          // legend entries ("" : none)
  std::vector<std::string> curve_styles;          // gnuplot "with ..." per curve ("" : a line)
  std::vector<std::string> labels;  // bars
  std::vector<std::pair<std::string, double>> marks;  // vertical lines at x (histogram: spec limits), in x's unit
  // panel: the curves' panel (0 on top) and each panel's y label; points with a label on panel 0
  std::vector<std::size_t> panel_of;
  std::vector<std::string> panel_ylabels;
  std::vector<std::tuple<double, double, std::string>> points;  // (x, y, label) drawn on the top panel
  std::string points_title;
  std::vector<std::string> arrows;  // "x0 y0 x1 y1" in the plot's units, drawn with a head (rotation)
  std::string caption;              // said under the plot
  // panel: a title inside each panel (small multiples: the node), and one y range for all panels
  std::vector<std::string> panel_titles;
  bool same_y = false;
  // lines: the x range drawn when it is not the curves' and marks' (a working range), and marks
  // beyond it, named at the plot's edge with their value
  std::optional<std::pair<double, double>> x_range;
  std::vector<std::pair<std::string, double>> edge_marks;
};

// Wide CSV: x and y columns of every curve side by side, shorter ones padded with empty cells.
// Headers and labels are user text: through csv_field, the one CSV quoting.
void write_figure_rows(std::ostream& out, const Figure& f) {
  out << std::setprecision(12);
  if (f.kind == Figure::Kind::bars) {
    const std::vector<double>& v = f.curves.front().second.values;
    out << "label," << csv_field(f.curves.front().second.name) << "\n";
    for (std::size_t i = 0; i < std::min(f.labels.size(), v.size()); ++i) out << csv_field(f.labels[i]) << "," << v[i] << "\n";
  } else {
    std::size_t rows = 0;
    for (std::size_t k = 0; k < f.curves.size(); ++k) {
      // Each curve's columns say whose it is: its legend entry, or in small multiples its panel's title.
      std::string whose = f.curve_titles[k];
      if (whose.empty() && k < f.panel_of.size() && f.panel_of[k] < f.panel_titles.size()) whose = f.panel_titles[f.panel_of[k]];
      const std::string prefix = f.curves.size() > 1 && !whose.empty() ? whose + " " : "";
      out << (k ? "," : "") << csv_field(prefix + f.curves[k].first.name) << "," << csv_field(prefix + f.curves[k].second.name);
      rows = std::max(rows, std::min(f.curves[k].first.values.size(), f.curves[k].second.values.size()));
    }
    out << "\n";
    for (std::size_t i = 0; i < rows; ++i) {
      for (std::size_t k = 0; k < f.curves.size(); ++k) {
        if (k) out << ",";
        const Column& x = f.curves[k].first;
        const Column& y = f.curves[k].second;
        if (i < x.values.size() && i < y.values.size()) out << x.values[i] << "," << y.values[i];
        else out << ",";
      }
      out << "\n";
    }
  }
}

void write_figure_csv(const std::filesystem::path& file, const Figure& f) {
  write_file_whole(file, true, [&](std::ostream& out) { write_figure_rows(out, f); });
}

// Vertical marks with their labels, staggered down the plot so that neighbours do not overprint.
void write_marks(std::ostream& s, const std::vector<std::pair<std::string, double>>& marks) {
  for (std::size_t k = 0; k < marks.size(); ++k) {
    const auto& [label, at] = marks[k];
    if (!std::isfinite(at)) continue;
    s << "set arrow from " << at << ", graph 0 to " << at << ", graph 1 nohead lw 1 dt 2 lc rgb '#c03030'\n"
      << "set label " << gnuplot_string(label) << " at " << at << ", graph " << 0.95 - 0.07 * static_cast<double>(k % 4)
      << " offset 0.4,0 font ',9' textcolor rgb '#c03030'\n";
  }
}

// Curve k is the datablock $curveK (x y), written by write_curve_data.
void write_curves(std::ostream& s, const Figure& f, const std::vector<std::size_t>& which) {
  s << "plot";
  bool first = true;
  for (std::size_t k : which) {
    const std::string style = k < f.curve_styles.size() && !f.curve_styles[k].empty() ? f.curve_styles[k] : "with lines lw 1.5";
    s << (first ? " " : ", \\\n    ") << "$curve" << k << " using 1:2 " << style
      << (f.curve_titles[k].empty() ? std::string(" notitle") : " title " + gnuplot_string(f.curve_titles[k]));
    first = false;
  }
}

// A derivative panel: one plot per quantity stacked on one angle axis, the x tics only under the
// bottom one, the legend once, the marks (dead centres) through every panel and the events as
// labelled points on the top one.
void write_panel(std::ostream& s, const Figure& f) {
  const std::size_t panels = f.panel_ylabels.size();
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& [x, y] : f.curves)
    for (double v : x.values) lo = std::min(lo, v), hi = std::max(hi, v);
  const double top = 0.93, bottom = 0.08, gap = 0.012, height = (top - bottom) / static_cast<double>(panels);
  // Room on the right for a legend only when a curve has a title.
  const bool keyed = std::any_of(f.curve_titles.begin(), f.curve_titles.end(), [](const std::string& t) { return !t.empty(); });
  s << "set multiplot title " << gnuplot_string(f.title) << "\nset xrange [" << lo << ":" << hi << "]\n"
    << "set lmargin at screen 0.11\nset rmargin at screen " << (keyed ? 0.76 : 0.95) << "\n";
  if (f.same_y) {
    // Small multiples share one y scale, so that the panels compare at a glance.
    double y_lo = std::numeric_limits<double>::infinity(), y_hi = -y_lo;
    for (const auto& [x, y] : f.curves)
      for (double v : y.values)
        if (std::isfinite(v)) y_lo = std::min(y_lo, v), y_hi = std::max(y_hi, v);
    const double pad = y_hi > y_lo ? 0.05 * (y_hi - y_lo) : std::max(1.0, std::abs(y_hi));
    if (std::isfinite(y_lo)) s << "set yrange [" << y_lo - pad << ":" << y_hi + pad << "]\n";
  }
  for (std::size_t p = 0; p < panels; ++p) {
    s << "set tmargin at screen " << top - height * static_cast<double>(p) << "\nset bmargin at screen "
      << top - height * static_cast<double>(p + 1) + gap << "\n";
    s << "unset arrow\nunset label\nset ylabel " << gnuplot_string(f.panel_ylabels[p]) << " font ',9'\n";
    if (p + 1 < panels) s << "set format x ''\nunset xlabel\n";
    else s << "set format x '%g'\nset xlabel " << gnuplot_string(f.xlabel) << "\n";
    if (p == 0) s << "set key outside right top\n";
    else s << "unset key\n";
    if (p < f.panel_titles.size())
      s << "set label " << gnuplot_string(f.panel_titles[p]) << " at graph 0.01, graph 0.9 left front font ',10'\n";
    write_marks(s, f.marks);
    std::vector<std::size_t> which;
    for (std::size_t k = 0; k < f.curves.size(); ++k)
      if (f.panel_of[k] == p) which.push_back(k);
    if (p == 0 && !f.points.empty()) {
      std::vector<double> xs, ys;
      for (const auto& [x, y, label] : f.points) xs.push_back(x), ys.push_back(y);
      write_gnuplot_datablock(s, "events", {&xs, &ys});
      for (const auto& [x, y, label] : f.points)
        if (!label.empty()) s << "set label " << gnuplot_string(label) << " at " << x << ", " << y << " offset 0.8,0.6 font ',9'\n";
      write_curves(s, f, which);
      s << ", \\\n    $events using 1:2 with points pt 7 ps 0.5 lc rgb 'black' title " << gnuplot_string(f.points_title) << "\n";
    } else {
      write_curves(s, f, which);
      s << "\n";
    }
  }
  s << "unset multiplot\n";
}

std::string run_gnuplot(const std::filesystem::path& dir, const Figure& f) {
  const std::string svg = f.name + ".svg", script_file = f.name + ".gp";
  write_file_whole(dir / script_file, true, [&](std::ostream& s) {
    const int height = f.kind == Figure::Kind::panel ? 160 * static_cast<int>(f.panel_ylabels.size()) + 90
                       : f.kind == Figure::Kind::to_scale ? 640 : 420;
    s << std::setprecision(17) << "set terminal svg size 860," << height << " dynamic noenhanced font 'sans,11' background rgb 'white'\n"
      << "set output " << gnuplot_string(svg) << "\n"
      << "set xlabel " << gnuplot_string(f.xlabel) << "\nset ylabel " << gnuplot_string(f.ylabel)
      << (f.ylabel.size() > 40 ? " font ',9'" : "") << "\n"
      << "set grid\nset key outside right top\n";
    if (f.kind != Figure::Kind::panel) s << "set title " << gnuplot_string(f.title) << "\n";
    // The data as numbers inside the script (gnuplot_data.hpp): gnuplot never reads the CSV
    // beside the plot, whose labels are the user's text.
    if (f.kind == Figure::Kind::bars) {
      std::vector<double> v = f.curves.front().second.values;
      v.resize(std::min(f.labels.size(), v.size()));
      write_gnuplot_datablock(s, "bars", {&v});
      s << "set style fill solid 0.6\nset boxwidth 0.6\nset yrange [0:*]\nunset key\n";
      write_gnuplot_xtic_labels(s, "rotate by -30", std::vector<std::string>(f.labels.begin(), f.labels.begin() + static_cast<long>(v.size())));
      s << "plot $bars using 0:1 with boxes lc rgb '#3060a0'\n";
    } else {
      for (std::size_t k = 0; k < f.curves.size(); ++k)
        write_gnuplot_datablock(s, "curve" + std::to_string(k), {&f.curves[k].first.values, &f.curves[k].second.values},
                                f.curves[k].second.pieces_from);
    }
    if (f.kind == Figure::Kind::bars) {
    } else if (f.kind == Figure::Kind::histogram) {
      // Bars that touch, one per bin, and the marks as dashed vertical lines. The x range holds the
      // bars and the marks within two data spans of them; a mark further out (a spec far from the
      // samples) is named in the title instead of squeezing the bars into a sliver.
      const std::vector<double>& x = f.curves.front().first.values;
      const double data_lo = x.front(), data_hi = x.back();
      const double scale = std::max({std::abs(data_lo), std::abs(data_hi), 1e-300});
      double span = data_hi - data_lo;
      if (!(span > 1e-9 * scale)) span = 1e-3 * scale;  // one bin (or bins too close to tell apart)
      const double width = x.size() > 1 ? span / static_cast<double>(x.size() - 1) : span;
      double lo = data_lo - 0.5 * width, hi = data_hi + 0.5 * width;
      std::string off_plot;
      std::vector<std::pair<std::string, double>> drawn;
      for (const auto& [label, at] : f.marks) {
        if (std::isfinite(at) && at >= data_lo - 2.0 * span - width && at <= data_hi + 2.0 * span + width) {
          drawn.emplace_back(label, at);
          lo = std::min(lo, at);
          hi = std::max(hi, at);
        } else {
          std::ostringstream m;
          m << std::setprecision(6) << label << " = " << at << (f.curves.front().first.unit.empty() ? "" : " " + f.curves.front().first.unit);
          off_plot += (off_plot.empty() ? "" : ", ") + m.str();
        }
      }
      const double pad = 0.04 * (hi - lo);
      if (!off_plot.empty()) s << "set title " << gnuplot_string(f.title + " (off the plot: " + off_plot + ")") << "\n";
      s << "set style fill solid 0.5 border rgb '#3060a0'\nset boxwidth " << width
        << " absolute\nset yrange [0:*]\nset xrange [" << lo - pad << ":" << hi + pad << "]\nunset key\n";
      for (const auto& [label, at] : drawn)
        s << "set arrow from " << at << ", graph 0 to " << at << ", graph 1 nohead lw 2 dt 2 lc rgb '#c03030'\n"
          << "set label " << gnuplot_string(label) << " at " << at << ", graph 0.95 offset 0.5,0 textcolor rgb '#c03030'\n";
      s << "plot $curve0 using 1:2 with boxes lc rgb '#3060a0'\n";
    } else if (f.kind == Figure::Kind::panel) {
      write_panel(s, f);
    } else {
      if (f.kind == Figure::Kind::to_scale) s << "set size ratio -1\n";
      for (const std::string& a : f.arrows) {
        std::istringstream in(a);
        double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
        in >> x0 >> y0 >> x1 >> y1;
        s << "set arrow from " << x0 << "," << y0 << " to " << x1 << "," << y1 << " head filled size screen 0.02,20 lw 1.5 lc rgb '#404040'\n";
      }
      if (f.x_range) {
        // A working range: the marks within it drawn, those beyond named at the edge they lie past.
        const auto [lo, hi] = *f.x_range;
        const double pad = 0.08 * (hi - lo);  // room for a mark's label right of its line
        s << "set xrange [" << lo - pad << ":" << hi + pad << "]\n";
        write_marks(s, f.marks);
        const std::string unit = f.curves.empty() ? std::string() : unit_without_reference(f.curves.front().first.unit);
        std::size_t left = 0, right = 0;
        for (const auto& [label, at] : f.edge_marks) {
          char value[48];
          std::snprintf(value, sizeof value, "%.4g", at);
          const std::string text = label + " at " + value + (unit.empty() ? "" : " " + unit);
          const bool before = at < lo;
          // Low on the plot: the marks' own labels stand at its top.
          const double y = 0.05 + 0.07 * static_cast<double>(before ? left++ : right++);
          s << "set label " << gnuplot_string(before ? "<- " + text : text + " ->") << " at graph " << (before ? 0.01 : 0.99)
            << ", graph " << y << (before ? " left" : " right") << " front font ',9' textcolor rgb '#c03030'\n";
        }
      } else if (!f.marks.empty()) {
        // The x range holds the curves and every mark.
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const auto& [x, y] : f.curves)
          for (double v : x.values) lo = std::min(lo, v), hi = std::max(hi, v);
        for (const auto& [label, at] : f.marks)
          if (std::isfinite(at)) lo = std::min(lo, at), hi = std::max(hi, at);
        const double pad = 0.06 * (hi - lo);
        s << "set xrange [" << lo - pad << ":" << hi + pad << "]\n";
        write_marks(s, f.marks);
      }
      std::vector<std::size_t> all(f.curves.size());
      for (std::size_t k = 0; k < all.size(); ++k) all[k] = k;
      write_curves(s, f, all);
      s << "\n";
    }
  });
  // gnuplot runs from an argument vector in the report's folder: no shell reads any name.
  const std::optional<std::filesystem::path> gnuplot = find_program("gnuplot");
  if (!gnuplot) throw IoError("mechgraph report draws its plots with gnuplot, which is not installed (apt-get install gnuplot-nox)");
  const SpawnOutcome run = run_program(*gnuplot, {script_file}, dir, dir / (f.name + ".log"), std::chrono::minutes(2));
  if (!run.succeeded()) {
    std::ifstream log(dir / (f.name + ".log"));
    std::string why(4096, '\0');
    log.read(why.data(), static_cast<std::streamsize>(why.size()));
    why.resize(static_cast<std::size_t>(log.gcount()));
    throw IoError("gnuplot failed on the plot " + quoted_text_excerpt(f.title) + " (" + run.describe() + "): " + utf8_sanitized(why));
  }
  std::string text;
  try {
    text = read_bounded_file(dir / svg, std::size_t{256} << 20);
  } catch (const FileReadError& e) {
    throw IoError("gnuplot wrote no SVG for the plot " + quoted_text_excerpt(f.title) + ": " + e.what());
  }
  // A plot cut short (a full disk) is refused, not inlined half.
  if (!is_whole_svg(text)) throw IoError("gnuplot wrote no whole SVG for the plot " + quoted_text_excerpt(f.title) + " (disk full?)");
  // Inline: drop the XML declaration and the DOCTYPE, keep <svg ...> ... </svg>.
  const auto begin = text.find("<svg");
  std::filesystem::remove(dir / svg);
  std::filesystem::remove(dir / script_file);
  std::filesystem::remove(dir / (f.name + ".log"));
  return text.substr(begin);
}

// The names legends use: a node's column title in the scene's report tables ("three-arc" for arc,
// v_arc and ta_arc), else the one column every node it feeds is in (a node that only one column's
// node reads is that column's), else the node's own name. A node in several
// columns (one that sums up the others) has no one column and keeps its name. Two curves of one
// figure that would read alike (three-arc by the source's rule and by the free-length rule) get
// the node's name beside.
class Legend {
 public:
  explicit Legend(const Graph& graph) {
    std::map<std::size_t, std::vector<std::string>> columns;  // node -> the distinct columns its cells are in
    for (const ResolvedReport& r : graph.reports)
      for (const auto& row : r.rows)
        for (std::size_t c = 0; c < row.cells.size() && c < r.columns.size(); ++c) {
          if (!row.cells[c] || row.cells[c]->output >= graph.outputs.size()) continue;
          auto& list = columns[graph.outputs[row.cells[c]->output].node];
          if (std::find(list.begin(), list.end(), r.columns[c]) == list.end()) list.push_back(r.columns[c]);
        }
    // Downstream: the nodes each node feeds.
    std::vector<std::vector<std::size_t>> feeds(graph.nodes.size());
    for (std::size_t n = 0; n < graph.nodes.size(); ++n)
      for (std::size_t up : graph.nodes[n].upstream)
        if (up < feeds.size()) feeds[up].push_back(n);
    for (std::size_t n = 0; n < graph.nodes.size(); ++n) {
      std::vector<std::string> found;
      if (const auto it = columns.find(n); it != columns.end()) {
        found = it->second;
      } else {
        // The columns of the nearest nodes downstream that are in a report table.
        std::vector<std::size_t> next = feeds[n];
        std::vector<bool> seen(graph.nodes.size(), false);
        while (!next.empty()) {
          const std::size_t m = next.back();
          next.pop_back();
          if (seen[m]) continue;
          seen[m] = true;
          if (const auto it = columns.find(m); it != columns.end()) {
            for (const std::string& c : it->second)
              if (std::find(found.begin(), found.end(), c) == found.end()) found.push_back(c);
          } else {
            next.insert(next.end(), feeds[m].begin(), feeds[m].end());
          }
        }
      }
      if (found.size() == 1) column_of_.emplace(graph.nodes[n].name, found.front());
    }
  }
  std::string operator()(const std::string& node) const {
    const auto it = column_of_.find(node);
    return it == column_of_.end() ? node : it->second;
  }
  // Curve titles made unique within a figure: a title that two nodes share (three-arc by the
  // source's rule and by the free-length rule) gets each node's name beside it.
  void disambiguate(Figure& f, const std::vector<std::string>& nodes) const {
    std::map<std::string, std::vector<std::string>> nodes_of;
    for (std::size_t k = 0; k < f.curve_titles.size() && k < nodes.size(); ++k) {
      auto& list = nodes_of[f.curve_titles[k]];
      if (std::find(list.begin(), list.end(), nodes[k]) == list.end()) list.push_back(nodes[k]);
    }
    for (std::size_t k = 0; k < f.curve_titles.size() && k < nodes.size(); ++k)
      if (nodes_of[f.curve_titles[k]].size() > 1 && f.curve_titles[k] != nodes[k]) f.curve_titles[k] += " (" + nodes[k] + ")";
  }

 private:
  std::map<std::string, std::string> column_of_;
};

std::string node_of(const OutputValue& o) { return o.label.substr(0, o.label.find('.')); }

// Names in a title, separated by ", ", or by "; " when a name has a comma of its own ("elastic,
// contacts (7500 rpm)").
std::string name_list(const std::vector<std::string>& names) {
  const bool commas = std::any_of(names.begin(), names.end(), [](const std::string& n) { return n.find(',') != std::string::npos; });
  std::string text;
  for (std::size_t k = 0; k < names.size(); ++k) text += (k ? (commas ? "; " : ", ") : "") + names[k];
  return text;
}

const OutputValue* find_output(const RunResult& result, const std::string& label) {
  for (const OutputValue& o : result.outputs)
    if (o.label == label) return &o;
  return nullptr;
}

// The axis values (SI) of every row of the events outputs (role events) of `o`'s node whose axis is
// the same quantity, in the same angle frame, as `o`'s table's: where the channels of `o` flagged
// jumps_at_events may jump.
std::vector<double> event_axis_values(const Graph& graph, const RunResult& result, const OutputValue& o) {
  const Table& t = o.value.as_table();
  const Presentation& mine = declared_port(graph, o.label).presentation();
  const std::string frame = mine.has_axis ? mine.axis.angle_frame : std::string();
  std::vector<double> at;
  for (const OutputValue& e : result.outputs) {
    if (&e == &o || node_of(e) != node_of(o) || e.value.kind() != ValueKind::table) continue;
    const Presentation& p = declared_port(graph, e.label).presentation();
    const Table& events = e.value.as_table();
    if (p.role != Role::events || !(events.axis.dimension == t.axis.dimension)) continue;
    if ((p.has_axis ? p.axis.angle_frame : std::string()) != frame) continue;
    at.insert(at.end(), events.axis.values.begin(), events.axis.values.end());
  }
  std::sort(at.begin(), at.end());
  return at;
}

// The rows of a curve over `axis` where a new piece starts because an event (sorted) lies after
// the row before it and at or before this row: no line is drawn across a jump.
std::vector<std::size_t> pieces_at(const std::vector<double>& axis, const std::vector<double>& events) {
  std::vector<std::size_t> from;
  if (events.empty()) return from;
  for (std::size_t i = 1; i < axis.size(); ++i) {
    const double lo = std::min(axis[i - 1], axis[i]), hi = std::max(axis[i - 1], axis[i]);
    const auto next = std::upper_bound(events.begin(), events.end(), lo);
    if (next != events.end() && *next <= hi) from.push_back(i);
  }
  return from;
}

// An angle quoted from the nearest of a frame's periodic marks: |a - mark| + before/after + the
// mark's label ("3.4 AM": 3.4 after the mark M). `deg` is the angle in degrees of the frame.
std::string from_nearest_mark(double deg, const AngleFrame& frame) {
  const double spacing = frame.mark_spacing * 180.0 / std::numbers::pi;
  const double k = std::round(deg / spacing);
  const long n = static_cast<long>(frame.mark_labels.size());
  const std::string& label = frame.mark_labels[static_cast<std::size_t>(((static_cast<long>(k) % n) + n) % n)];
  const double from = deg - k * spacing;
  char text[48];
  std::snprintf(text, sizeof text, "%.1f ", std::abs(from));
  return text + (from < 0.0 ? frame.before : frame.after) + label;
}

// The tag of a column's degrees: its declared frame's, else for a rate per angle (mm/deg) the
// frame of the table's axis; "" when neither says.
std::string column_tag(const DeclaredPort& d, const std::string& name, const Dimension& dimension) {
  if (const ChannelDecl* c = d.channel(name); c && !c->angle_frame.empty()) return d.tag(c->angle_frame);
  const Presentation& p = d.presentation();
  if (dimension.angle < 0 && p.has_axis) return d.tag(p.axis.angle_frame);
  return {};
}

// A derivative family (role derivative_family: a value and its derivatives over one axis, every
// node's table of one port): one plot per order stacked on the axis. When the axis' frame has a
// derived frame (this = scale * axis + offset_param) and every node drawn is given that parameter,
// the panel is drawn in the derived frame, with its periodic marks and the points the port declares
// (another output's row, labelled and quoted from the nearest mark); else over the axis.
Figure derivative_panel(const Graph& graph, const RunResult& result, const std::vector<const OutputValue*>& outs,
                        const std::string& stem, const std::string& port, const Legend& legend) {
  const DisplayUnits& units = graph.display_units;
  const DeclaredPort first = declared_port(graph, outs.front()->label);
  const Presentation& p = first.presentation();
  Figure f;
  f.kind = Figure::Kind::panel;
  f.name = file_safe(stem + "_" + port);
  std::vector<std::string> nodes;
  std::vector<std::string> names, id_list;
  for (const OutputValue* o : outs) names.push_back(legend(node_of(*o))), id_list.push_back(node_of(*o));
  const std::string who = name_list(names), ids = name_list(id_list);
  f.title = (p.figure_title.empty() ? spoken(port) : p.figure_title) + " of " + who + (who == ids ? "" : " (" + ids + ")");
  std::vector<const ChannelDecl*> orders;
  for (const ChannelDecl& c : p.channels)
    if (c.derivative_order >= 0) orders.push_back(&c);
  std::stable_sort(orders.begin(), orders.end(), [](const ChannelDecl* a, const ChannelDecl* b) { return a->derivative_order < b->derivative_order; });
  // The derived frame, when every node gives its offset.
  const AngleFrame* derived = nullptr;
  if (first.info && p.has_axis && !p.axis.angle_frame.empty())
    for (const AngleFrame& fr : first.info->frames)
      if (!derived && fr.base_frame == p.axis.angle_frame && !fr.offset_param.empty()) derived = &fr;
  std::vector<double> offset;  // SI, per node
  for (const OutputValue* o : outs) {
    const DeclaredPort d = declared_port(graph, o->label);
    if (!derived || !d.node || !d.node->params.has(derived->offset_param)) {
      offset.clear();
      break;
    }
    offset.push_back(d.node->params.number(derived->offset_param));
  }
  if (offset.size() != outs.size()) derived = nullptr;
  for (std::size_t q = 0; q < orders.size(); ++q) {
    std::string ylabel;
    for (std::size_t k = 0; k < outs.size(); ++k) {
      const Table& t = outs[k]->value.as_table();
      const DeclaredPort d = declared_port(graph, outs[k]->label);
      const Table::Column* c = t.find(orders[q]->name);
      if (!c) continue;
      Column x;
      if (derived) {
        std::vector<double> shifted = t.axis.values;
        for (double& v : shifted) v = derived->scale * v + offset[k];
        x = shown(derived->label, t.axis.dimension, shifted, t.axis.display_unit, units, derived->unit_tag);
      } else {
        x = shown(d.label(t.axis.name), t.axis.dimension, t.axis.values, t.axis.display_unit, units, column_tag(d, t.axis.name, t.axis.dimension));
      }
      Column y = shown(d.label(c->name), c->dimension, c->values, c->display_unit, units, column_tag(d, c->name, c->dimension));
      ylabel = y.name;
      f.xlabel = x.name;
      f.curves.emplace_back(std::move(x), std::move(y));
      f.curve_titles.push_back(legend(node_of(*outs[k])));
      f.curve_styles.emplace_back();
      f.panel_of.push_back(f.panel_ylabels.size());
      nodes.push_back(node_of(*outs[k]));
    }
    f.panel_ylabels.push_back(ylabel);
  }
  legend.disambiguate(f, nodes);
  if (!derived || f.curves.empty()) return f;
  if (derived->mark_spacing > 0.0 && !derived->mark_labels.empty()) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& [x, y] : f.curves)
      for (double v : x.values) lo = std::min(lo, v), hi = std::max(hi, v);
    const double spacing = to_unit(derived->mark_spacing, dim::angle, unit_without_reference(f.curves.front().first.unit));
    const long n = static_cast<long>(derived->mark_labels.size());
    for (double mark = spacing * std::ceil(lo / spacing); mark <= hi; mark += spacing)
      f.marks.emplace_back(derived->mark_labels[static_cast<std::size_t>(((std::lround(mark / spacing) % n) + n) % n)], mark);
  }
  // The points other outputs of each node put on the panel (those in the derived frame), on the top plot.
  const std::string y_unit = unit_without_reference(f.curves.front().second.unit), angle_unit = unit_without_reference(f.curves.front().first.unit);
  for (const PointMarks& pm : p.points) {
    for (std::size_t k = 0; k < outs.size(); ++k) {
      const OutputValue* source = find_output(result, node_of(*outs[k]) + "." + pm.port);
      if (!source || source->value.kind() != ValueKind::table) continue;
      const Table& e = source->value.as_table();
      if (e.axis.values.size() <= pm.row) continue;
      const DeclaredPort from = declared_port(graph, source->label);
      const double y = pm.y_from_axis ? to_unit(e.axis.values[pm.row], e.axis.dimension, y_unit.empty() ? e.axis.dimension.si_unit() : y_unit) : 0.0;
      std::string quote;
      std::vector<std::tuple<double, double, std::string>> points;
      for (std::size_t j = 0; j < pm.x_channels.size(); ++j) {
        const Table::Column* c = e.find(pm.x_channels[j]);
        const ChannelDecl* decl = from.channel(pm.x_channels[j]);
        if (!c || c->values.size() <= pm.row || !decl || decl->angle_frame != derived->id) {
          points.clear();
          break;
        }
        const double deg = c->values[pm.row] * 180.0 / std::numbers::pi;
        const std::string label = j < pm.labels.size() ? pm.labels[j] : pm.x_channels[j];
        const std::string said = derived->mark_spacing > 0.0 && !derived->mark_labels.empty() ? label + " " + from_nearest_mark(deg, *derived) : label;
        quote += (quote.empty() ? "" : ", ") + said;
        // One node's points are labelled on the plot; several nodes' are said in the caption.
        points.emplace_back(to_unit(c->values[pm.row], dim::angle, angle_unit), y, outs.size() == 1 ? said : "");
      }
      if (points.empty()) continue;
      f.points.insert(f.points.end(), points.begin(), points.end());
      std::string title = pm.caption;
      if (const auto at = title.find("{axis}"); at != std::string::npos) {
        char value[48];
        std::snprintf(value, sizeof value, "%g", y);
        title.replace(at, 6, value + (y_unit.empty() ? std::string() : " " + y_unit));
      }
      f.points_title = title;
      f.caption += (f.caption.empty() ? title + ": " : "; ") + f.curve_titles[k] + " " + quote;
    }
  }
  return f;
}

// A table drawn over one of its channels (role curve_over_channel: x_channel), a figure per node:
// every drawn channel of the x channel's... of one dimension over it, styled by its flags, with the
// table's marks on the x axis.
Figure curve_over_channel(const Graph& graph, const OutputValue& o, const Legend& legend) {
  const DisplayUnits& units = graph.display_units;
  const DeclaredPort d = declared_port(graph, o.label);
  const Presentation& p = d.presentation();
  const Table& t = o.value.as_table();
  const std::string node = node_of(o);
  Figure f;
  const Table::Column* xc = t.find(p.x_channel);
  if (!xc) return f;
  const std::string x_words = d.label(p.x_channel);
  f.name = file_safe(o.label + "_over_" + x_words.substr(x_words.rfind(' ') + 1));
  f.title = (p.figure_title.empty() ? spoken(o.label) + " over " + d.label(p.x_channel) : p.figure_title) + " of " + legend(node) +
            (legend(node) == node ? "" : " (" + node + ")");
  const Column x = shown(d.label(xc->name), xc->dimension, xc->values, xc->display_unit, units, column_tag(d, xc->name, xc->dimension));
  f.xlabel = x.name;
  const std::string x_unit = x.unit.empty() ? xc->dimension.si_unit() : unit_without_reference(x.unit);
  auto mark_at = [&](const std::string& label) -> std::optional<double> {
    for (const Table::Mark& m : t.axis_marks)
      if (m.label == label) return to_unit(m.value, xc->dimension, x_unit);
    return std::nullopt;
  };
  std::optional<Dimension> drawn;
  for (const Table::Column& c : t.channels) {
    const ChannelDecl* decl = d.channel(c.name);
    const std::uint32_t flags = decl ? decl->flags : 0u;
    if (c.name == p.x_channel || (flags & (channel_flag::alt_axis | channel_flag::not_drawn | channel_flag::curvature)) != 0) continue;
    if (drawn && !(c.dimension == *drawn)) continue;  // one quantity per figure: the first's
    drawn = c.dimension;
    Column y = shown(d.label(c.name), c.dimension, c.values, c.display_unit, units, column_tag(d, c.name, c.dimension));
    f.ylabel = quantity(c.dimension) + " [" + y.unit + "]";
    Column cx = x;
    std::string style;
    if (flags & channel_flag::positive_only) {
      Column keep_x = cx, keep_y = y;
      keep_x.values.clear();
      keep_y.values.clear();
      for (std::size_t i = 0; i < y.values.size(); ++i)
        if (y.values[i] > 0.0) keep_x.values.push_back(cx.values[i]), keep_y.values.push_back(y.values[i]);
      cx = std::move(keep_x);
      y = std::move(keep_y);
      style = "with lines lw 1.5 dt 2";
    } else if (flags & channel_flag::line_from_mark) {
      // A straight line: from the mark (at 0) to the row of the largest x.
      const std::optional<double> from = decl ? mark_at(decl->from_mark) : std::nullopt;
      if (from && !cx.values.empty()) {
        std::size_t top = 0;
        for (std::size_t i = 0; i < cx.values.size(); ++i)
          if (cx.values[i] > cx.values[top]) top = i;
        cx.values = {*from, cx.values[top]};
        y.values = {0.0, y.values[top]};
        style = "with linespoints lw 2 pt 7 ps 0.5";
      }
    }
    if (cx.values.empty()) continue;
    f.curve_styles.push_back(style);
    f.curve_titles.push_back(d.label(c.name));
    f.curves.emplace_back(std::move(cx), std::move(y));
  }
  for (const Table::Mark& m : t.axis_marks) f.marks.emplace_back(m.label, to_unit(m.value, xc->dimension, x_unit));
  // A working range (the x channel flagged range_of_rows): what the rows span and the marks near
  // it; a mark beyond it by more than a quarter of the span is named at the plot's edge instead,
  // and a line from it is cut there.
  const ChannelDecl* x_decl = d.channel(p.x_channel);
  if (x_decl && (x_decl->flags & channel_flag::range_of_rows) != 0 && !x.values.empty()) {
    const auto [least, greatest] = std::minmax_element(x.values.begin(), x.values.end());
    double lo = *least, hi = *greatest;
    const double reach = 0.25 * (hi - lo);
    std::vector<std::pair<std::string, double>> near;
    for (const auto& [label, at] : f.marks) {
      if (at >= *least - reach && at <= *greatest + reach) {
        near.emplace_back(label, at);
        lo = std::min(lo, at);
        hi = std::max(hi, at);
      } else {
        f.edge_marks.emplace_back(label, at);
      }
    }
    if (hi > lo) {
      f.marks = std::move(near);
      f.x_range = std::make_pair(lo, hi);
    } else {
      f.edge_marks.clear();
    }
  }
  f.caption = p.caption;
  return f;
}

// A drawing to scale (role drawing_to_scale): its declared x/y pairs (0 an outline, 1 a
// construction line, 2 a part shown at rest), the least circle about the origin of the first
// outline, and an arrow showing the way the part turns (Table::turns_clockwise).
Figure drawing_figure(const OutputValue& o, const Presentation& presentation, const DisplayUnits& units, const Legend& legend) {
  const Table& t = o.value.as_table();
  Figure f;
  f.kind = Figure::Kind::to_scale;
  f.name = file_safe(o.label);
  const std::string node = node_of(o), name = legend(node);
  f.title = spoken(o.label.substr(o.label.find('.') + 1)) + " of " + name + (name == node ? "" : " (" + node + ")") + " (to scale)";
  std::optional<std::size_t> outline;  // the first outline (stroke 0)
  for (const XyPair& pair : presentation.pairs) {
    const Table::Column* xc = t.find(pair.x);
    const Table::Column* y = t.find(pair.y);
    if (!xc || !y) continue;
    const Table::Column& c = *xc;
    Column cx = shown("x", c.dimension, c.values, c.display_unit, units), cy = shown("y", y->dimension, y->values, y->display_unit, units);
    // Close an outline or a construction line: the first point again at the end (a part at rest
    // is drawn as its path goes).
    if (pair.stroke != 2 && !cx.values.empty()) {
      cx.values.push_back(cx.values.front());
      cy.values.push_back(cy.values.front());
    }
    f.xlabel = cx.name;
    f.ylabel = cy.name;
    if (pair.stroke == 0 && !outline) outline = f.curves.size();
    f.curve_titles.push_back(pair.label.empty() ? pair.layer : pair.label);
    f.curve_styles.push_back(pair.stroke == 0 ? "with lines lw 2 lc rgb '#204080'" : pair.stroke == 1 ? "with lines lw 1 dt 3 lc rgb '#808080'"
                                                                                     : "with lines lw 2 lc rgb '#c03030'");
    f.curves.emplace_back(std::move(cx), std::move(cy));
  }
  if (f.curves.empty() || !outline) return f;
  const std::vector<double> X = f.curves[*outline].first.values;  // copies: f.curves grows below
  const std::vector<double> Y = f.curves[*outline].second.values;
  const std::string unit = f.curves[*outline].first.unit;
  double r_base = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < X.size(); ++i) r_base = std::min(r_base, std::hypot(X[i], Y[i]));
  auto circle = [&](double cx, double cy, double r, std::size_t n) {
    std::pair<Column, Column> c;
    c.first.name = "x [" + unit + "]";
    c.second.name = "y [" + unit + "]";
    c.first.unit = c.second.unit = unit;
    for (std::size_t i = 0; i <= n; ++i) {
      const double a = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
      c.first.values.push_back(cx + r * std::cos(a));
      c.second.values.push_back(cy + r * std::sin(a));
    }
    return c;
  };
  char base_title[64];
  std::snprintf(base_title, sizeof base_title, "least circle r = %.4g %s", r_base, unit.c_str());
  f.curves.push_back(circle(0.0, 0.0, r_base, 180));
  f.curve_titles.push_back(base_title);
  f.curve_styles.push_back("with lines lw 1 dt 2 lc rgb '#a0a0a0'");
  // The rotation: an arc of a third of a turn at half the least radius, its head the way the part
  // turns (data of the table: turns_clockwise).
  const bool clockwise = t.turns_clockwise;
  const double r_arrow = 0.5 * r_base;
  std::pair<Column, Column> arc;
  arc.first.name = "rotation x [" + unit + "]";
  arc.second.name = "rotation y [" + unit + "]";
  arc.first.unit = arc.second.unit = unit;
  const double from = clockwise ? 2.4 : 0.7, to = clockwise ? 0.7 : 2.4;
  for (int i = 0; i <= 30; ++i) {
    const double a = from + (to - from) * i / 30.0;
    arc.first.values.push_back(r_arrow * std::cos(a));
    arc.second.values.push_back(r_arrow * std::sin(a));
  }
  std::ostringstream head;
  head << std::setprecision(12) << arc.first.values[28] << " " << arc.second.values[28] << " " << arc.first.values[30] << " "
       << arc.second.values[30];
  f.arrows.push_back(head.str());
  f.curves.push_back(std::move(arc));
  f.curve_titles.push_back(clockwise ? "rotation (clockwise)" : "rotation (counter-clockwise)");
  f.curve_styles.push_back("with lines lw 1.5 lc rgb '#404040'");
  return f;
}

// The figures a run's outputs call for.
std::vector<Figure> plan_figures(const Graph& graph, const RunResult& result, std::vector<const OutputValue*>& small) {
  const DisplayUnits& units = graph.display_units;
  const Legend legend(graph);
  std::vector<Figure> figures;
  std::map<std::string, std::vector<const OutputValue*>> by_port, series_by_port;  // grouped by port name
  std::vector<std::string> port_order, series_order;
  std::map<std::string, std::string> port_of, first_node_of;  // table group -> port name, its first node
  std::map<std::string, int> groups_of_port;
  for (const OutputValue& o : result.outputs) {
    const std::string port = o.label.substr(o.label.find('.') + 1);
    const std::string node = node_of(o);
    if (o.value.kind() == ValueKind::table) {
      const Table& t = o.value.as_table();
      if (t.closed_curve) {
        Figure f = drawing_figure(o, declared_port(graph, o.label).presentation(), units, legend);
        if (!f.curves.empty()) figures.push_back(std::move(f));
        continue;
      }
      if (t.histogram && !t.channels.empty() && !t.axis.values.empty()) {
        Figure f;
        f.kind = Figure::Kind::histogram;
        f.name = file_safe(o.label);
        f.title = o.label + (t.axis_marks.empty() ? std::string() : " against the spec limits");
        Column x = shown(t.axis.name, t.axis.dimension, t.axis.values, t.axis.display_unit, units);
        Column y = shown(t.channels.front().name, t.channels.front().dimension, t.channels.front().values,
                         t.channels.front().display_unit, units);
        std::vector<double> at;
        for (const Table::Mark& m : t.axis_marks) at.push_back(m.value);
        const Column marks = shown("", t.axis.dimension, at, t.axis.display_unit, units);
        for (std::size_t k = 0; k < at.size(); ++k) f.marks.emplace_back(t.axis_marks[k].label, marks.values[k]);
        f.xlabel = x.name;
        f.ylabel = y.name;
        f.curve_titles.push_back(o.label);
        f.curves.emplace_back(std::move(x), std::move(y));
        figures.push_back(std::move(f));
        continue;
      }
      // A list of events (role events) is read as a table however long it is: a plot of event
      // codes over an axis says nothing.
      if (t.axis.values.size() <= table_rows_shown || declared_port(graph, o.label).presentation().role == Role::events) {
        small.push_back(&o);
        continue;
      }
      // Tables of one port are compared when their channels agree (rates over an angle and rates in
      // time are two groups).
      std::string group = port + "\x1f" + t.axis.name + ":" + t.axis.dimension.describe();
      for (const Table::Column& c : t.channels) group += "\x1f" + c.name + ":" + c.dimension.describe();
      if (!by_port.count(group)) {
        port_order.push_back(group);
        port_of[group] = port;
        first_node_of[group] = node;
        ++groups_of_port[port];
      }
      by_port[group].push_back(&o);
    } else if (o.value.kind() == ValueKind::series) {
      const Series& s = o.value.as_series();
      if (s.labels.size() == s.values.size() && !s.values.empty()) {
        Figure f;
        f.kind = Figure::Kind::bars;
        f.name = file_safe(o.label);
        f.title = o.label;
        Column v = shown(port, o.dimension, s.values, o.display_unit, units);
        f.ylabel = v.name;
        f.labels = s.labels;
        f.curves.emplace_back(Column{}, std::move(v));
        f.curve_titles.push_back(o.label);
        figures.push_back(std::move(f));
      } else if (s.values.size() > table_rows_shown) {
        if (!series_by_port.count(port)) series_order.push_back(port);
        series_by_port[port].push_back(&o);
      }
    }
  }
  // Series of one port name: one plot, a curve per node. A series over an angle is over the angle
  // frame its port declares (labelled by the frame) and is drawn in degrees.
  for (const std::string& port : series_order) {
    Figure f;
    f.name = file_safe(port);
    std::string base = port;
    if (base.size() > 6 && base.compare(base.size() - 6, 6, "_curve") == 0) base = base.substr(0, base.size() - 6);
    f.title = spoken(port);
    std::vector<std::string> nodes;
    for (const OutputValue* o : series_by_port[port]) {
      const Series& s = o->value.as_series();
      const bool angle = s.axis_dimension == dim::angle;
      const DeclaredPort d = declared_port(graph, o->label);
      const AngleFrame* frame = angle && d.port ? d.frame(d.port->angle_frame) : nullptr;
      Column x = shown(frame ? frame->label : angle ? "angle" : "axis", s.axis_dimension, s.axis, angle ? "deg" : "", units,
                       frame ? frame->unit_tag : "");
      Column y = shown(base, o->dimension, s.values, o->display_unit, units);
      f.xlabel = x.name;
      f.ylabel = y.name;
      f.curve_titles.push_back(legend(node_of(*o)));
      nodes.push_back(node_of(*o));
      f.curves.emplace_back(std::move(x), std::move(y));
    }
    legend.disambiguate(f, nodes);
    figures.push_back(std::move(f));
  }
  for (const std::string& group : port_order) {
    const auto& outs = by_port[group];
    const std::string& port = port_of[group];
    // Names and titles say which nodes when one port has several groups.
    const bool named = groups_of_port[port] > 1;
    const std::string stem = named ? port + "_" + first_node_of[group] : port;
    const Table& first = outs.front()->value.as_table();
    const DeclaredPort declared = declared_port(graph, outs.front()->label);
    const Presentation& presentation = declared.presentation();
    if (presentation.role == Role::derivative_family) {
      figures.push_back(derivative_panel(graph, result, outs, stem, port, legend));
      continue;
    }
    if (presentation.role == Role::curve_over_channel && first.find(presentation.x_channel)) {
      for (const OutputValue* o : outs) figures.push_back(curve_over_channel(graph, *o, legend));
      continue;
    }
    // Channels another scale of the axis or not drawn are left out; a radius of curvature is drawn
    // as curvature, apart.
    auto flags_of = [&](const Table::Column& c) {
      const ChannelDecl* decl = declared.channel(c.name);
      return decl ? decl->flags : 0u;
    };
    auto apart = [&](const Table::Column& c) { return (flags_of(c) & (channel_flag::alt_axis | channel_flag::not_drawn | channel_flag::curvature)) != 0; };
    auto is_curvature_radius = [&](const Table::Column& c) { return (flags_of(c) & channel_flag::curvature) != 0; };
    // Channels that share a dimension with another channel of the table are compared within one
    // node's table (a force against its requirement, a computed against a prescribed motion); a
    // channel with a dimension of its own is compared across nodes (every node's acceleration).
    // A radius of curvature is drawn as curvature, on its own.
    std::vector<Dimension> dims;
    std::map<std::size_t, int> channels_of;  // index in dims -> channels of that dimension
    for (const Table::Column& c : first.channels) {
      if (apart(c)) continue;
      auto it = std::find(dims.begin(), dims.end(), c.dimension);
      if (it == dims.end()) it = dims.insert(dims.end(), c.dimension);
      ++channels_of[static_cast<std::size_t>(it - dims.begin())];
    }
    auto shared_dimension = [&](const Table::Column& c) {
      const auto it = std::find(dims.begin(), dims.end(), c.dimension);
      return it != dims.end() && channels_of[static_cast<std::size_t>(it - dims.begin())] > 1;
    };
    auto who = [&](const std::vector<const OutputValue*>& list) {
      std::vector<std::string> names;
      for (const OutputValue* o : list) names.push_back(legend(node_of(*o)));
      return name_list(names);
    };
    // A plain table's declared figure title names a figure of all its drawn channels; a figure of
    // some of them adds which ("Seal gaps over a turn: upper gap").
    std::size_t drawn = 0;
    for (const Table::Column& c : first.channels) drawn += apart(c) ? 0 : 1;
    auto titled = [&](const std::string& what, std::size_t channels) {
      if (presentation.figure_title.empty()) return what;
      return channels == drawn ? presentation.figure_title : presentation.figure_title + ": " + what;
    };
    // Curvature of every node's table together.
    for (const Table::Column& channel : first.channels) {
      if (!is_curvature_radius(channel)) continue;
      Figure f;
      f.name = file_safe(stem + "_curvature");
      f.title = "Curvature 1/rho of " + who(outs) + " (0 at an inflection; least radius ";
      std::vector<std::string> nodes;
      std::string least;
      for (const OutputValue* o : outs) {
        const Table& t = o->value.as_table();
        const Table::Column* c = t.find(channel.name);
        if (!c) continue;
        const Column x = shown(declared.label(t.axis.name), t.axis.dimension, t.axis.values, t.axis.display_unit, units,
                               column_tag(declared, t.axis.name, t.axis.dimension));
        auto curve = curvature_of(x, c->values, "curvature");
        double rho = std::numeric_limits<double>::infinity();
        for (double v : c->values)
          if (v > 0.0) rho = std::min(rho, v);
        char text[64];
        std::snprintf(text, sizeof text, "%s%.4g mm", least.empty() ? "" : ", ", rho * 1e3);
        least += (outs.size() > 1 ? legend(node_of(*o)) + " " : std::string()) + text;
        f.xlabel = curve.first.name;
        f.ylabel = curve.second.name;
        f.curve_titles.push_back(legend(node_of(*o)));
        nodes.push_back(node_of(*o));
        f.curves.push_back(std::move(curve));
      }
      f.title += least + ")";
      legend.disambiguate(f, nodes);
      if (!f.curves.empty()) figures.push_back(std::move(f));
    }
    // A channel flagged jumps_at_events is drawn in pieces between its node's events.
    auto pieces = [&](const OutputValue& o, const Table::Column& c) {
      return (flags_of(c) & channel_flag::jumps_at_events) != 0 ? pieces_at(o.value.as_table().axis.values, event_axis_values(graph, result, o))
                                                              : std::vector<std::size_t>{};
    };
    if (outs.size() > 1) {
      // Several nodes' tables: a plot per lone channel, a curve per node; more nodes than an
      // overlay keeps apart are small multiples instead, a panel per node on one x axis and one y
      // scale.
      const bool multiples = outs.size() > overlaid_at_most;
      for (const Table::Column& channel : first.channels) {
        if (apart(channel) || shared_dimension(channel)) continue;
        Figure f;
        f.name = file_safe(stem + "_" + channel.name);
        const std::string all = who(outs);
        f.title = titled(declared.label(channel.name), 1) + (multiples ? ", a panel per node"
                                                  : all.size() <= 70 ? " of " + all : ", a curve per node (the legend)");
        std::vector<std::string> nodes;
        for (const OutputValue* o : outs) {
          const Table& t = o->value.as_table();
          const Table::Column* c = t.find(channel.name);
          if (!c) continue;
          Column x = shown(declared.label(t.axis.name), t.axis.dimension, t.axis.values, t.axis.display_unit, units,
                           column_tag(declared, t.axis.name, t.axis.dimension));
          Column y = shown(declared.label(channel.name), c->dimension, c->values, c->display_unit, units,
                           column_tag(declared, channel.name, c->dimension));
          y.pieces_from = pieces(*o, *c);
          f.xlabel = x.name;
          f.ylabel = y.name;
          f.curve_titles.push_back(legend(node_of(*o)));
          nodes.push_back(node_of(*o));
          if (multiples) {
            f.panel_of.push_back(f.panel_ylabels.size());
            f.panel_ylabels.push_back(y.name);
          }
          f.curves.emplace_back(std::move(x), std::move(y));
        }
        legend.disambiguate(f, nodes);
        if (multiples) {
          // Each panel says its node; the curves need no legend.
          f.kind = Figure::Kind::panel;
          f.same_y = true;
          f.panel_titles = f.curve_titles;
          f.curve_titles.assign(f.curves.size(), std::string());
        }
        figures.push_back(std::move(f));
      }
    }
    // Each node's table: its channels grouped by dimension, a plot per group (with several nodes,
    // only the groups of more than one channel: the lone ones were overlaid above).
    for (const OutputValue* o : outs) {
      const Table& t = o->value.as_table();
      for (std::size_t g = 0; g < dims.size(); ++g) {
        if (outs.size() > 1 && channels_of[g] < 2) continue;
        Figure f;
        std::string names;
        std::vector<std::string> spoken_names;
        for (const Table::Column& c : t.channels) {
          if (apart(c) || !(c.dimension == dims[g])) continue;
          Column x = shown(declared.label(t.axis.name), t.axis.dimension, t.axis.values, t.axis.display_unit, units,
                           column_tag(declared, t.axis.name, t.axis.dimension));
          Column y = shown(declared.label(c.name), c.dimension, c.values, c.display_unit, units, column_tag(declared, c.name, c.dimension));
          y.pieces_from = pieces(*o, c);
          f.xlabel = x.name;
          spoken_names.push_back(declared.label(c.name));
          f.ylabel = y.unit;
          f.curve_titles.push_back(declared.label(c.name));
          names += (names.empty() ? "" : ", ") + declared.label(c.name);
          f.curves.emplace_back(std::move(x), std::move(y));
        }
        if (f.curves.empty()) continue;
        // The y axis names what is drawn: the channels, else (too many to read) the quantity.
        const std::string what = names.size() <= 60 ? names : quantity(dims[g]);
        f.ylabel = f.ylabel.empty() ? what : what + " [" + f.ylabel + "]";
        const std::string name = legend(node_of(*o));
        f.title = titled(names, f.curves.size()) + " of " + name + (name == node_of(*o) ? "" : " (" + node_of(*o) + ")");
        f.name = file_safe(o->label + "_" + f.curve_titles.front());
        figures.push_back(std::move(f));
      }
    }
  }
  return figures;
}

// Print. An A4 page less its 12 mm margins is 186 mm wide, 65.9 em of a table's 8 pt; a table
// wider than that would be cut at the page's edge, so it is printed in parts instead: column
// groups that each repeat the table's key columns (a report row's label and unit, an events
// table's axis). The screen keeps the whole table and scrolls sideways.
constexpr double printed_width_em = 65.9;

// The width in em of the table's 8 pt that a column needs in print, estimated from its text with
// a little to spare (chromium's sans-serif is Liberation Sans, Arial's widths: digits 0.56 em;
// DejaVu Sans, where it stands in, is wider). A header wraps between its words and keeps its unit
// whole; numbers never wrap; a text cell (a row's label) wraps too, at most 24 letters wide.
double print_width_em(const std::string& header, const std::string& unit, const std::vector<std::string>& cells,
                      bool text_cells, double header_size) {
  double widest = 0.0;
  std::istringstream words(header);
  for (std::string word; words >> word;) widest = std::max(widest, 0.62 * header_size * static_cast<double>(word.size()));
  if (!unit.empty()) widest = std::max(widest, 0.55 * header_size * static_cast<double>(unit.size() + 2));
  for (const std::string& cell : cells)
    widest = std::max(widest, text_cells ? 0.6 * static_cast<double>(std::min<std::size_t>(cell.size(), 24))
                                         : 0.64 * static_cast<double>(cell.size()));
  return widest + 1.25;  // padding 6 px each side and the border
}

// The printed parts of a table: each the key columns [0, keys) and then the next columns that fit
// the page. A part ends where the unit changes (degrees of one frame to another's) when that keeps at
// least half of what would fit, so a part holds one kind of column. One part: the table fits.
std::vector<std::vector<std::size_t>> print_parts(const std::vector<double>& width_em, std::size_t keys,
                                                  const std::vector<std::string>& unit) {
  double key_width = 0.0;
  for (std::size_t k = 0; k < keys && k < width_em.size(); ++k) key_width += width_em[k];
  std::vector<std::vector<std::size_t>> parts;
  std::size_t next = keys;
  while (next < width_em.size()) {
    std::vector<std::size_t> part;
    double used = key_width;
    // At least one column per part, whatever its width (the page cannot be wider).
    while (next < width_em.size() && (part.empty() || used + width_em[next] <= printed_width_em)) {
      used += width_em[next];
      part.push_back(next++);
    }
    if (next < width_em.size()) {
      std::size_t cut = part.size();
      for (std::size_t j = part.size() - 1; j >= (part.size() + 1) / 2 && j > 0; --j)
        if (unit[part[j]] != unit[part[j - 1]]) {
          cut = j;
          break;
        }
      next -= part.size() - cut;
      part.resize(cut);
    }
    parts.push_back(std::move(part));
  }
  return parts;
}

// A table of the page: `header` cells as HTML, `body` cells as text; the first `keys` columns name
// a row (text, left-aligned), the rest are numbers. A table too wide for the printed page is
// shown whole on screen and printed in parts (print_parts), each with the key columns.
struct PageTable {
  std::string table_class;  // "" or "narrow" (headers of a name and a unit)
  std::vector<std::string> header_html;
  std::vector<std::string> header_text, header_unit;  // for the print width
  std::vector<std::vector<std::string>> body;
  std::size_t keys = 0;
  bool text_keys = false;  // the key columns are text (a report row's label), not numbers
};

void write_html_table(std::ostream& html, const PageTable& t, const std::string& table_class, const std::vector<std::size_t>& columns,
                      const std::string& caption) {
  html << "<table" << (table_class.empty() ? std::string() : " class=\"" + table_class + "\"") << ">\n";
  if (!caption.empty()) html << "<caption>" << html_text(caption) << "</caption>\n";
  html << "<tr>";
  for (std::size_t k : columns) html << "<th>" << t.header_html[k] << "</th>";
  html << "</tr>\n";
  for (const std::vector<std::string>& row : t.body) {
    html << "<tr>";
    for (std::size_t k : columns) html << (k < t.keys && t.text_keys ? "<td>" : "<td class=\"n\">") << html_text(row[k]) << "</td>";
    html << "</tr>\n";
  }
  html << "</table>";
}

void write_page_table(std::ostream& html, const PageTable& t) {
  const bool narrow = t.table_class == "narrow";
  std::vector<double> width(t.header_html.size());
  for (std::size_t k = 0; k < width.size(); ++k) {
    std::vector<std::string> cells;
    for (const auto& row : t.body) cells.push_back(row[k]);
    width[k] = print_width_em(t.header_text[k], t.header_unit[k], cells, k < t.keys && t.text_keys, narrow ? 0.85 : 1.0);
  }
  const std::vector<std::vector<std::size_t>> parts = print_parts(width, t.keys, t.header_unit);
  std::vector<std::size_t> all(t.header_html.size());
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = k;
  html << (parts.size() > 1 ? "<div class=\"scroll screen\">" : "<div class=\"scroll\">");
  write_html_table(html, t, t.table_class, all, "");
  html << "</div>\n";
  if (parts.size() < 2) return;
  html << "<div class=\"print\">\n";
  for (std::size_t p = 0; p < parts.size(); ++p) {
    std::vector<std::size_t> columns(all.begin(), all.begin() + static_cast<long>(t.keys));
    columns.insert(columns.end(), parts[p].begin(), parts[p].end());
    write_html_table(html, t, t.table_class.empty() ? "part" : t.table_class + " part", columns,
                     "part " + std::to_string(p + 1) + " of " + std::to_string(parts.size()));
    html << "\n";
  }
  html << "</div>\n";
}

void html_table(std::ostream& html, const std::vector<std::vector<std::string>>& rows, const std::string& csv) {
  PageTable t;
  t.keys = 2;  // the row's label and unit
  t.text_keys = true;
  for (const std::string& h : rows.front()) {
    t.header_html.push_back(html_text(h));
    t.header_text.push_back(h);
    t.header_unit.emplace_back();
  }
  t.body.assign(rows.begin() + 1, rows.end());
  write_page_table(html, t);
  html << "<p class=\"csv\">data: " << html_text(csv) << "</p>\n";
}

}  // namespace

void write_report_page(const std::filesystem::path& dir, const Graph& graph, const RunResult& result,
                       const PluginRegistry& registry, const RunInputs& inputs) {
  if (!find_program("gnuplot"))
    throw IoError("mechgraph report draws its plots with gnuplot, which is not installed (apt-get install gnuplot-nox)");
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" << html_text(graph.title)
       << "</title>\n<style>\nbody{font-family:sans-serif;margin:2em auto;max-width:960px;color:#222}\n"
          "table{border-collapse:collapse;margin:0.5em 0;font-size:90%}td,th{border:1px solid #bbb;padding:2px 6px}"
          "th{background:#eef;font-weight:600;vertical-align:bottom}td.n{text-align:right;font-variant-numeric:tabular-nums}\n"
          "table.narrow th{font-size:85%;max-width:7em}.u{font-weight:normal;color:#555;white-space:nowrap}.scroll{max-width:100%;overflow-x:auto}\n"
          ".csv{color:#666;font-size:90%}figure{margin:1em 0;break-inside:avoid}svg{max-width:100%;height:auto}\n"
          // Print: A4, tables at 8 pt; a table too wide for the page is printed in parts (.print) instead
          // of whole (.screen), see print_parts.
          ".print{display:none}caption{text-align:left;font-size:85%;color:#555}\n"
          "@page{size:A4;margin:12mm}@media print{body{margin:0;max-width:none;font-size:10pt}h2{break-after:avoid}"
          "table{font-size:8pt;break-inside:avoid}.screen{display:none}.print{display:block}.scroll{overflow:visible}}\n"
          "</style></head><body>\n"
       << "<h1>" << html_text(graph.title.empty() ? inputs.scene_file : graph.title) << "</h1>\n";
  html << "<p>mechgraph " << MECHGRAPH_VERSION << ", scene <code>" << html_text(inputs.scene_file) << "</code> (SHA-1 "
       << file_sha1(inputs.scene_file) << ")";
  if (!inputs.overrides.empty()) {
    html << ", with";
    for (const std::string& o : inputs.overrides) html << " <code>--set " << html_text(o) << "</code>";
  }
  html << ". Plugins:";
  // Those the evaluated nodes come from, as results.json lists them (not whatever else was loaded).
  std::set<std::string> used;
  for (std::size_t index : graph.order) used.insert(graph.nodes[index].type->plugin_id);
  for (const PluginInfo& p : registry.plugins())
    if (used.count(p.id)) html << " " << html_text(p.id) << " " << html_text(p.version) << ";";
  html << " everything in <code>results.json</code>.</p>\n";

  // The scene's report tables.
  for (std::size_t t = 0; t < graph.reports.size(); ++t) {
    const ResolvedReport& r = graph.reports[t];
    const std::string csv = "table_" + std::to_string(t + 1) + ".csv";
    write_report_csv(dir / csv, r, result, graph);
    html << "<h2>" << html_text(r.title.empty() ? "Table " + std::to_string(t + 1) : r.title) << "</h2>\n";
    html_table(html, report_cells(r, result, graph), csv);
  }

  std::vector<const OutputValue*> small;
  const std::vector<Figure> figures = plan_figures(graph, result, small);
  if (!figures.empty()) html << "<h2>Plots</h2>\n";
  for (std::size_t i = 0; i < figures.size(); ++i) {
    Figure f = figures[i];
    f.name = "plot_" + std::to_string(i + 1) + "_" + f.name;
    write_figure_csv(dir / (f.name + ".csv"), f);
    html << "<figure>" << run_gnuplot(dir, f) << "<figcaption class=\"csv\">" << (f.caption.empty() ? "" : html_text(f.caption) + "; ")
         << "data: " << html_text(f.name) << ".csv</figcaption></figure>\n";
  }
  for (const OutputValue* o : small) {
    const std::string csv = file_safe(o->label) + ".csv";
    const Table& t = o->value.as_table();
    PageTable page_table;
    page_table.table_class = "narrow";
    page_table.keys = 1;  // the axis
    std::vector<const Table::Column*> cols{&t.axis};
    for (const Table::Column& c : t.channels) cols.push_back(&c);
    // Angles in degrees and lengths in millimetres unless the scene says otherwise; a table with
    // angles of more than one declared frame says of each angle column which angle it is.
    const DeclaredPort declared = declared_port(graph, o->label);
    std::vector<std::string> frames_seen;
    for (const Table::Column* c : cols)
      if (const ChannelDecl* decl = declared.channel(c->name); decl && !decl->angle_frame.empty() &&
          std::find(frames_seen.begin(), frames_seen.end(), decl->angle_frame) == frames_seen.end())
        frames_seen.push_back(decl->angle_frame);
    std::vector<std::string> unit;
    for (const Table::Column* c : cols) {
      unit.push_back(display_unit(c->dimension, c->display_unit, graph.display_units));
      const ChannelDecl* decl = declared.channel(c->name);
      const std::string tag = frames_seen.size() > 1 && decl ? declared.tag(decl->angle_frame) : std::string();
      page_table.header_unit.push_back(unit_with_reference(unit.back().empty() ? c->dimension.si_unit() : unit.back(), tag));
      page_table.header_text.push_back(declared.label(c->name));
      page_table.header_html.push_back(html_text(page_table.header_text.back()) + "<br><span class=\"u\">[" +
                                       html_text(page_table.header_unit.back()) + "]</span>");
    }
    // The CSV beside the table is in the units the table shows.
    write_table_csv(dir / csv, t, unit, declared);
    for (std::size_t i = 0; i < t.axis.values.size(); ++i) {
      std::vector<std::string> row;
      for (std::size_t k = 0; k < cols.size(); ++k) {
        // A code is shown by its declared name, its number beside it ("contact_lost (1)").
        const ChannelDecl* decl = declared.channel(cols[k]->name);
        const std::string_view name = decl ? decl->code_name(cols[k]->values[i]) : std::string_view();
        const double v = unit[k].empty() ? cols[k]->values[i] : to_unit(cols[k]->values[i], cols[k]->dimension, unit[k]);
        const std::string number = shown_number(v, cols[k]->values[i], noise_floor(cols[k]->dimension, table_largest(t, cols[k]->dimension)));
        row.push_back(name.empty() ? number : std::string(name) + " (" + number + ")");
      }
      page_table.body.push_back(std::move(row));
    }
    html << "<h2>" << html_text(o->label) << "</h2>\n";
    write_page_table(html, page_table);
    // What the table is, in its port's own words (an events table's codes are explained there).
    std::string doc;
    for (const RequestedOutput& r : graph.outputs)
      if (r.label == o->label && r.spec) doc = r.spec->doc;
    html << "<p class=\"csv\">" << (doc.empty() ? "" : html_text(doc) + "; ") << "data: " << html_text(csv) << "</p>\n";
  }
  // How the results were made.
  bool first = true;
  for (const NodeRun& r : result.runs)
    for (const std::string& n : r.notes) {
      if (first) html << "<h2>Notes</h2>\n<ul>\n";
      first = false;
      html << "<li>" << html_text(r.node) << ": " << html_text(n) << "</li>\n";
    }
  if (!first) html << "</ul>\n";
  html << "</body></html>\n";

  write_file_whole(dir / "report.html", true, [&](std::ostream& page) { page << html.str(); });
  write_file_whole(dir / "results.json", true, [&](std::ostream& json) { write_json(json, graph, result, registry, inputs); });
  spdlog::info("report: {} plots, {} tables", figures.size(), graph.reports.size() + small.size());
}

}  // namespace mechgraph::cli
