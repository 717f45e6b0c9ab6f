#include "report_page.hpp"

#include "result_files.hpp"
#include "results_folder.hpp"
#include "spawn.hpp"

#include <mechgraph/csv.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/bounded_read.hpp>
#include <mechgraph/text_escape.hpp>
#include <mechgraph/units.hpp>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

#ifndef MECHGRAPH_VERSION
#define MECHGRAPH_VERSION "0"
#endif

namespace mechgraph::cli {
namespace {

// Tables with at most this many rows are shown as tables, not plotted (a cam's events).
constexpr std::size_t table_rows_shown = 12;

std::string file_safe(std::string text) {
  for (char& c : text)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_')) c = '_';
  return text;
}

// A column to plot: values converted to the unit shown.
// A plot's axis title for a dimension: the quantity's name where it has one ("force", not
// "mass*length/time^2"), else the dimension in base quantities.
std::string quantity(const Dimension& d) {
  static const std::pair<Dimension, const char*> named[] = {
      {dim::force, "force"},           {dim::stress, "stress"},
      {dim::velocity, "velocity"},     {dim::acceleration, "acceleration"},
      {dim::stiffness, "stiffness"},   {dim::length / dim::time.pow(3), "jerk"},
      {dim::frequency, "frequency"},   {dim::angular_speed, "angular speed"},
      {dim::force * dim::length, "moment"}};
  for (const auto& [known, name] : named)
    if (known == d) return name;
  return d.describe();
}

struct Column {
  std::string name;   // CSV header: "kurz lift [mm]"
  std::string unit;
  std::vector<double> values;
};

Column shown(const std::string& title, const Dimension& d, const std::vector<double>& si, const std::string& own_unit,
             const DisplayUnits& units) {
  Column c;
  c.unit = units.unit_for(d, own_unit);
  if (c.unit.empty()) c.unit = d.si_unit() == "1" ? std::string() : d.si_unit();
  c.values.reserve(si.size());
  const bool convert = !units.unit_for(d, own_unit).empty();
  for (double v : si) c.values.push_back(convert ? to_unit(v, d, c.unit) : v);
  c.name = title + (c.unit.empty() ? std::string() : " [" + c.unit + "]");
  return c;
}

struct Figure {
  enum class Kind { lines, bars, to_scale, histogram } kind = Kind::lines;
  std::string name;  // file stem
  std::string title, xlabel, ylabel;
  std::vector<std::pair<Column, Column>> curves;  // (x, y) per curve; bars: x unused, labels below
  std::vector<std::string> curve_titles;
  std::vector<std::string> labels;  // bars
  std::vector<std::pair<std::string, double>> marks;  // vertical lines at x (histogram: spec limits), in x's unit
};

// Wide CSV: x and y columns of every curve side by side, shorter ones padded with empty cells.
// Headers and labels are user text: through csv_field, the one CSV quoting.
void write_figure_csv(const std::filesystem::path& file, const Figure& f) {
  std::ofstream out(file);
  if (!out) throw IoError("cannot write '" + file.string() + "'");
  out << std::setprecision(12);
  if (f.kind == Figure::Kind::bars) {
    const std::vector<double>& v = f.curves.front().second.values;
    out << "label," << csv_field(f.curves.front().second.name) << "\n";
    for (std::size_t i = 0; i < std::min(f.labels.size(), v.size()); ++i) out << csv_field(f.labels[i]) << "," << v[i] << "\n";
  } else {
    std::size_t rows = 0;
    for (std::size_t k = 0; k < f.curves.size(); ++k) {
      const std::string prefix = f.curves.size() > 1 ? f.curve_titles[k] + " " : "";
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
  out.close();
  check_written(out, file);
}

std::string run_gnuplot(const std::filesystem::path& dir, const Figure& f) {
  const std::string csv = f.name + ".csv", svg = f.name + ".svg", script_file = f.name + ".gp";
  {
    std::ofstream s(dir / script_file);
    s << "set terminal svg size 860,420 dynamic noenhanced font 'sans,11' background rgb 'white'\n"
      << "set output " << gnuplot_string(svg) << "\n"
      << "set datafile separator ','\nset datafile missing ''\n"
      << "set title " << gnuplot_string(f.title) << "\nset xlabel " << gnuplot_string(f.xlabel) << "\nset ylabel "
      << gnuplot_string(f.ylabel) << "\n"
      << "set grid\nset key outside right top\n";
    if (f.kind == Figure::Kind::bars) {
      s << "set style fill solid 0.6\nset boxwidth 0.6\nset yrange [0:*]\nset xtics rotate by -30\nunset key\n"
        << "plot " << gnuplot_string(csv) << " skip 1 using 0:2:xtic(1) with boxes lc rgb '#3060a0'\n";
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
      s << std::setprecision(17) << "set style fill solid 0.5 border rgb '#3060a0'\nset boxwidth " << width
        << " absolute\nset yrange [0:*]\nset xrange [" << lo - pad << ":" << hi + pad << "]\nunset key\n";
      for (const auto& [label, at] : drawn)
        s << "set arrow from " << at << ", graph 0 to " << at << ", graph 1 nohead lw 2 dt 2 lc rgb '#c03030'\n"
          << "set label " << gnuplot_string(label) << " at " << at << ", graph 0.95 offset 0.5,0 textcolor rgb '#c03030'\n";
      s << "plot " << gnuplot_string(csv) << " skip 1 using 1:2 with boxes lc rgb '#3060a0'\n";
    } else {
      if (f.kind == Figure::Kind::to_scale) s << "set size ratio -1\n";
      s << "plot";
      for (std::size_t k = 0; k < f.curves.size(); ++k)
        s << (k ? ", \\\n    " : " ") << gnuplot_string(csv) << " skip 1 using " << 2 * k + 1 << ":" << 2 * k + 2
          << " with lines lw 1.5 title " << gnuplot_string(f.curve_titles[k]);
      s << "\n";
    }
    s.close();
    check_written(s, dir / script_file);
  }
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
  std::ifstream in(dir / svg);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Inline: drop the XML declaration and the DOCTYPE, keep <svg ...> ... </svg>.
  const auto begin = text.find("<svg");
  if (begin == std::string::npos) throw IoError("gnuplot wrote no SVG for the plot " + quoted_text_excerpt(f.title));
  std::filesystem::remove(dir / svg);
  std::filesystem::remove(dir / script_file);
  std::filesystem::remove(dir / (f.name + ".log"));
  return text.substr(begin);
}

// The figures a run's outputs call for.
std::vector<Figure> plan_figures(const Graph& graph, const RunResult& result, std::vector<const OutputValue*>& small) {
  const DisplayUnits& units = graph.display_units;
  std::vector<Figure> figures;
  std::map<std::string, std::vector<const OutputValue*>> by_port, series_by_port;  // grouped by port name
  std::vector<std::string> port_order, series_order;
  std::map<std::string, std::string> port_of, first_node_of;  // table group -> port name, its first node
  std::map<std::string, int> groups_of_port;
  for (const OutputValue& o : result.outputs) {
    const std::string port = o.label.substr(o.label.find('.') + 1);
    const std::string node = o.label.substr(0, o.label.find('.'));
    if (o.value.kind() == ValueKind::table) {
      const Table& t = o.value.as_table();
      if (t.closed_curve) {
        Figure f;
        f.kind = Figure::Kind::to_scale;
        f.name = file_safe(o.label);
        f.title = o.label + " (to scale)";
        for (const Table::Column& c : t.channels) {
          if (c.name.size() < 1 || c.name.back() != 'x' || (c.name != "x" && c.name.size() > 2 && c.name.substr(c.name.size() - 2) != "_x")) continue;
          const std::string prefix = c.name == "x" ? "" : c.name.substr(0, c.name.size() - 2);
          const Table::Column* y = t.find(prefix.empty() ? "y" : prefix + "_y");
          if (!y) continue;
          Column cx = shown("x", c.dimension, c.values, c.display_unit, units), cy = shown("y", y->dimension, y->values, y->display_unit, units);
          // Close the drawing: the first point again at the end.
          cx.values.push_back(cx.values.front());
          cy.values.push_back(cy.values.front());
          f.xlabel = cx.name;
          f.ylabel = cy.name;
          f.curve_titles.push_back(prefix.empty() ? "contour" : prefix + " curve");
          f.curves.emplace_back(std::move(cx), std::move(cy));
        }
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
      if (t.axis.values.size() <= table_rows_shown) {
        small.push_back(&o);
        continue;
      }
      // Tables of one port are compared when their channels agree (a cam's svaj over cam angle, a
      // valve's in time are two groups).
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
  // Series of one port name (every valve's lift curve): one plot, a curve per node.
  for (const std::string& port : series_order) {
    Figure f;
    f.name = file_safe(port);
    f.title = port;
    for (const OutputValue* o : series_by_port[port]) {
      const Series& s = o->value.as_series();
      Column x = shown("axis", s.axis_dimension, s.axis, "", units), y = shown(port, o->dimension, s.values, o->display_unit, units);
      f.xlabel = x.name;
      f.ylabel = y.name;
      f.curve_titles.push_back(o->label.substr(0, o->label.find('.')));
      f.curves.emplace_back(std::move(x), std::move(y));
    }
    figures.push_back(std::move(f));
  }
  for (const std::string& group : port_order) {
    const auto& outs = by_port[group];
    const std::string& port = port_of[group];
    // Names and titles say which nodes when one port has several groups.
    const bool named = groups_of_port[port] > 1;
    const std::string stem = named ? port + "_" + first_node_of[group] : port;
    const Table& first = outs.front()->value.as_table();
    // Channels that share a dimension with another channel of the table are compared within one
    // node's table (a spring line against its requirement, dynamic against kinematic lift); a
    // channel with a dimension of its own is compared across nodes (every cam's acceleration).
    std::vector<Dimension> dims;
    std::map<std::size_t, int> channels_of;  // index in dims -> channels of that dimension
    for (const Table::Column& c : first.channels) {
      if (c.name == "crank_angle") continue;  // the axis again, doubled
      auto it = std::find(dims.begin(), dims.end(), c.dimension);
      if (it == dims.end()) it = dims.insert(dims.end(), c.dimension);
      ++channels_of[static_cast<std::size_t>(it - dims.begin())];
    }
    auto shared_dimension = [&](const Table::Column& c) {
      const auto it = std::find(dims.begin(), dims.end(), c.dimension);
      return it != dims.end() && channels_of[static_cast<std::size_t>(it - dims.begin())] > 1;
    };
    if (outs.size() > 1) {
      // Several nodes' tables: a plot per lone channel, a curve per node.
      for (const Table::Column& channel : first.channels) {
        if (channel.name == "crank_angle" || shared_dimension(channel)) continue;
        Figure f;
        f.name = file_safe(stem + "_" + channel.name);
        f.title = port + ": " + channel.name;
        if (named) {
          f.title = port + " of ";
          for (std::size_t k = 0; k < outs.size(); ++k) f.title += (k ? ", " : "") + outs[k]->label.substr(0, outs[k]->label.find('.'));
          f.title += ": " + channel.name;
        }
        for (const OutputValue* o : outs) {
          const Table& t = o->value.as_table();
          const Table::Column* c = t.find(channel.name);
          if (!c) continue;
          Column x = shown(t.axis.name, t.axis.dimension, t.axis.values, t.axis.display_unit, units);
          Column y = shown(channel.name, c->dimension, c->values, c->display_unit, units);
          f.xlabel = x.name;
          f.ylabel = y.name;
          f.curve_titles.push_back(o->label.substr(0, o->label.find('.')));
          f.curves.emplace_back(std::move(x), std::move(y));
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
        f.title = o->label;
        std::string names;
        for (const Table::Column& c : t.channels) {
          if (c.name == "crank_angle" || !(c.dimension == dims[g])) continue;
          Column x = shown(t.axis.name, t.axis.dimension, t.axis.values, t.axis.display_unit, units);
          Column y = shown(c.name, c.dimension, c.values, c.display_unit, units);
          f.xlabel = x.name;
          f.ylabel = y.unit.empty() ? quantity(dims[g]) : quantity(dims[g]) + " [" + y.unit + "]";
          f.curve_titles.push_back(c.name);
          names += (names.empty() ? "" : ", ") + c.name;
          f.curves.emplace_back(std::move(x), std::move(y));
        }
        if (f.curves.empty()) continue;
        f.title += ": " + names;
        f.name = file_safe(o->label + "_" + f.curve_titles.front());
        figures.push_back(std::move(f));
      }
    }
  }
  return figures;
}

void html_table(std::ostream& html, const std::vector<std::vector<std::string>>& rows, const std::string& csv) {
  html << "<table>\n<tr>";
  for (const std::string& h : rows.front()) html << "<th>" << html_text(h) << "</th>";
  html << "</tr>\n";
  for (std::size_t r = 1; r < rows.size(); ++r) {
    html << "<tr>";
    for (std::size_t i = 0; i < rows[r].size(); ++i) html << (i < 2 ? "<td>" : "<td class=\"n\">") << html_text(rows[r][i]) << "</td>";
    html << "</tr>\n";
  }
  html << "</table>\n<p class=\"csv\">data: " << html_text(csv) << "</p>\n";
}

}  // namespace

void write_report_page(const std::filesystem::path& dir, const Graph& graph, const RunResult& result,
                       const PluginRegistry& registry, const RunInputs& inputs) {
  if (!find_program("gnuplot"))
    throw IoError("mechgraph report draws its plots with gnuplot, which is not installed (apt-get install gnuplot-nox)");
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" << html_text(graph.title)
       << "</title>\n<style>\nbody{font-family:sans-serif;margin:2em auto;max-width:960px;color:#222}\n"
          "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #bbb;padding:3px 8px}"
          "th{background:#eef}td.n{text-align:right;font-variant-numeric:tabular-nums}\n"
          ".csv{color:#666;font-size:90%}figure{margin:1em 0}svg{max-width:100%;height:auto}\n</style></head><body>\n"
       << "<h1>" << html_text(graph.title.empty() ? inputs.scene_file : graph.title) << "</h1>\n";
  html << "<p>mechgraph " << MECHGRAPH_VERSION << ", scene <code>" << html_text(inputs.scene_file) << "</code> (SHA-1 "
       << file_sha1(inputs.scene_file) << ")";
  if (!inputs.overrides.empty()) {
    html << ", with";
    for (const std::string& o : inputs.overrides) html << " <code>--set " << html_text(o) << "</code>";
  }
  html << ". Plugins:";
  for (const PluginInfo& p : registry.plugins()) html << " " << html_text(p.id) << " " << html_text(p.version) << ";";
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
    html << "<figure>" << run_gnuplot(dir, f) << "<figcaption class=\"csv\">data: " << html_text(f.name) << ".csv</figcaption></figure>\n";
  }
  for (const OutputValue* o : small) {
    const std::string csv = file_safe(o->label) + ".csv";
    write_table_csv(dir / csv, o->value.as_table(), graph.display_units);
    const Table& t = o->value.as_table();
    std::vector<std::vector<std::string>> rows(1);
    std::vector<const Table::Column*> cols{&t.axis};
    for (const Table::Column& c : t.channels) cols.push_back(&c);
    std::vector<std::string> unit;
    for (const Table::Column* c : cols) {
      unit.push_back(graph.display_units.unit_for(c->dimension, c->display_unit));
      rows[0].push_back(c->name + " [" + (unit.back().empty() ? c->dimension.si_unit() : unit.back()) + "]");
    }
    for (std::size_t i = 0; i < t.axis.values.size(); ++i) {
      std::vector<std::string> row;
      for (std::size_t k = 0; k < cols.size(); ++k) {
        const double v = unit[k].empty() ? cols[k]->values[i] : to_unit(cols[k]->values[i], cols[k]->dimension, unit[k]);
        char buffer[32];
        std::snprintf(buffer, sizeof buffer, "%.6g", v);
        row.push_back(buffer);
      }
      rows.push_back(std::move(row));
    }
    html << "<h2>" << html_text(o->label) << "</h2>\n<table>\n<tr>";
    for (const std::string& h : rows[0]) html << "<th>" << html_text(h) << "</th>";
    html << "</tr>\n";
    for (std::size_t r = 1; r < rows.size(); ++r) {
      html << "<tr>";
      for (const std::string& c : rows[r]) html << "<td class=\"n\">" << c << "</td>";
      html << "</tr>\n";
    }
    html << "</table>\n<p class=\"csv\">data: " << html_text(csv) << "</p>\n";
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

  std::ofstream page(dir / "report.html");
  page << html.str();
  page.close();
  check_written(page, dir / "report.html");
  std::ofstream json(dir / "results.json");
  write_json(json, graph, result, registry, inputs);
  json.close();
  check_written(json, dir / "results.json");
  spdlog::info("report: {} plots, {} tables", figures.size(), graph.reports.size() + small.size());
}

}  // namespace mechgraph::cli
