#include "study_page.hpp"
#include "study_text.hpp"

#include <mechgraph/text_escape.hpp>
#include <mechgraph/units.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mechgraph::cli {
namespace {

// A histogram as SVG bars over [low, high], the spec limits as dashed red lines.
std::string histogram_svg(const OutputAnswer& o) {
  const Histogram& h = o.histogram;
  constexpr double width = 560, height = 200, left = 10, bottom = 170, plot_w = 540, plot_h = 150;
  const double low = h.low, high = h.low + h.width * static_cast<double>(h.counts.size());
  const std::size_t most = std::max<std::size_t>(1, *std::max_element(h.counts.begin(), h.counts.end()));
  const auto x_of = [&](double v) { return left + (v - low) / (high - low) * plot_w; };
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height << "\" role=\"img\">\n";
  for (std::size_t k = 0; k < h.counts.size(); ++k) {
    const double bar = static_cast<double>(h.counts[k]) / static_cast<double>(most) * plot_h;
    s << "<rect x=\"" << study_number(x_of(low + h.width * static_cast<double>(k))) << "\" y=\"" << study_number(bottom - bar) << "\" width=\""
      << study_number(std::max(plot_w / static_cast<double>(h.counts.size()) - 1, 0.5)) << "\" height=\"" << study_number(bar)
      << "\" fill=\"#4a78b0\"><title>" << h.counts[k] << "</title></rect>\n";
  }
  s << "<line x1=\"" << left << "\" y1=\"" << bottom << "\" x2=\"" << left + plot_w << "\" y2=\"" << bottom << "\" stroke=\"black\"/>\n";
  for (const auto& [limit, name] : {std::pair{o.lower, "LSL"}, std::pair{o.upper, "USL"}}) {
    if (!limit) continue;
    const double x = x_of(*limit);
    // The label right of its line, or left of it where it would run past the picture's edge (an
    // upper limit that bounds the histogram, the usual case): about 6.5 px a character at 11 px.
    const std::string label = std::string(name) + " " + study_number(*limit);
    const bool room_right = x + 3 + 6.5 * static_cast<double>(label.size()) <= width;
    s << "<line x1=\"" << study_number(x) << "\" y1=\"12\" x2=\"" << study_number(x) << "\" y2=\"" << bottom
      << "\" stroke=\"#c0392b\" stroke-dasharray=\"5,3\"/>\n<text x=\"" << study_number(room_right ? x + 3 : x - 3) << "\" y=\"22\" font-size=\"11\" fill=\"#c0392b\""
      << (room_right ? "" : " text-anchor=\"end\"") << ">" << html_text(label) << "</text>\n";
  }
  s << "<text x=\"" << left << "\" y=\"188\" font-size=\"11\">" << study_number(low) << "</text>\n<text x=\"" << left + plot_w
    << "\" y=\"188\" font-size=\"11\" text-anchor=\"end\">" << study_number(high) << " " << html_text(study_unit(o.column)) << "</text>\n</svg>\n";
  return s.str();
}

// First-order (dark) and total (light) indices per parameter with their intervals as whiskers.
std::string sobol_svg(const StudySpec& spec, const SobolIndices& si) {
  // The axis spans [0, 1] and what the indices and intervals reach beyond it, up to a quarter each
  // side: a wide interval of few samples ([-780, 2277]) would shrink every bar to a line. Whatever
  // lies past the axis is drawn to its end, marked by an arrowhead.
  constexpr double reach = 0.25;
  double lo = 0.0, hi = 1.0;
  for (const SobolIndex& i : si.indices)
    for (const std::optional<double>& v : {std::optional<double>(i.first), std::optional<double>(i.total), i.first_interval.lower,
                                           i.total_interval.lower, i.first_interval.upper, i.total_interval.upper})
      if (v) lo = std::min(lo, *v), hi = std::max(hi, *v);
  lo = std::max(lo, -reach);
  hi = std::min(hi, 1.0 + reach);
  constexpr double name_w = 150, plot_w = 380, row_h = 34;
  const double height = 30 + row_h * static_cast<double>(si.indices.size());
  const auto x_of = [&](double v) { return name_w + (std::clamp(v, lo, hi) - lo) / (hi - lo) * plot_w; };
  const auto arrowhead = [](std::ostringstream& out, double x, double y, bool right) {
    const double tip = right ? x + 6 : x - 6;
    out << "<polygon points=\"" << study_number(x) << "," << study_number(y - 4) << " " << study_number(tip) << "," << study_number(y) << " " << study_number(x) << "," << study_number(y + 4)
        << "\" fill=\"black\"/>\n";
  };
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << name_w + plot_w + 20 << "\" height=\"" << study_number(height) << "\" role=\"img\">\n";
  for (std::size_t j = 0; j < si.indices.size(); ++j) {
    const SobolIndex& i = si.indices[j];
    const double y = 10 + row_h * static_cast<double>(j);
    s << "<text x=\"" << name_w - 6 << "\" y=\"" << study_number(y + 16) << "\" font-size=\"12\" text-anchor=\"end\">" << html_text(spec.parameters[j].name)
      << "</text>\n";
    const auto bar = [&](double value, const Interval& in, double top, const char* colour, const char* what) {
      const double a = x_of(std::min(0.0, value)), b = x_of(std::max(0.0, value));
      s << "<rect x=\"" << study_number(a) << "\" y=\"" << study_number(top) << "\" width=\"" << study_number(std::max(b - a, 0.5)) << "\" height=\"11\" fill=\"" << colour
        << "\"><title>" << what << " " << study_number(value) << " [" << study_number(in.lower) << ", " << study_number(in.upper) << "]</title></rect>\n";
      if (in.lower && in.upper) {
        s << "<line x1=\"" << study_number(x_of(*in.lower)) << "\" y1=\"" << study_number(top + 5.5) << "\" x2=\"" << study_number(x_of(*in.upper)) << "\" y2=\""
          << study_number(top + 5.5) << "\" stroke=\"black\"/>\n";
        if (*in.lower < lo) arrowhead(s, x_of(lo), top + 5.5, false);
        if (*in.upper > hi) arrowhead(s, x_of(hi), top + 5.5, true);
      }
    };
    bar(i.first, i.first_interval, y + 2, "#2c5d8f", "first order");
    bar(i.total, i.total_interval, y + 15, "#9cc3e6", "total");
  }
  const double axis = 10 + row_h * static_cast<double>(si.indices.size());
  s << "<line x1=\"" << study_number(x_of(0)) << "\" y1=\"6\" x2=\"" << study_number(x_of(0)) << "\" y2=\"" << study_number(axis) << "\" stroke=\"black\"/>\n";
  s << "<line x1=\"" << study_number(x_of(1)) << "\" y1=\"6\" x2=\"" << study_number(x_of(1)) << "\" y2=\"" << study_number(axis) << "\" stroke=\"#999\" stroke-dasharray=\"3,3\"/>\n";
  s << "<text x=\"" << study_number(x_of(0)) << "\" y=\"" << study_number(axis + 14) << "\" font-size=\"11\" text-anchor=\"middle\">0</text>\n";
  s << "<text x=\"" << study_number(x_of(1)) << "\" y=\"" << study_number(axis + 14) << "\" font-size=\"11\" text-anchor=\"middle\">1</text>\n</svg>\n";
  return s.str();
}

}  // namespace

std::string study_page(const std::string& title, const StudySpec& spec, const StudyAnswers& a) {
  std::ostringstream p;
  const std::string level = confidence_percent(spec.confidence);
  p << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << html_text(title.empty() ? "Uncertainty study" : title)
    << "</title>\n<style>body{font-family:sans-serif;max-width:60em;margin:1em auto}table{border-collapse:collapse}"
       "td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}td:first-child,th:first-child,.text{text-align:left}</style></head><body>\n";
  p << "<h1>" << html_text(title.empty() ? "Uncertainty study" : title) << "</h1>\n<p>" << html_text(to_string(spec.method)) << ", "
    << spec.samples << " samples, seed " << spec.seed << ", " << a.cases << " evaluations (" << a.failed << " failed); intervals at "
    << level << " %.</p>\n<h2>Parameters</h2>\n<table><tr><th>parameter</th><th>distribution</th><th>mean</th><th>standard deviation</th></tr>\n";
  for (const UncertainParameter& q : spec.parameters) {
    // In the unit the distribution was written in (a spread scaled, not shifted), else SI.
    double scale = 1.0, offset = 0.0;
    std::string unit = q.unit;
    if (!unit.empty()) {
      try {
        const UnitScale u = parse_unit(" " + unit);
        scale = u.scale;
        offset = u.offset;
      } catch (const UnitError&) {
        unit.clear();
      }
    }
    if (unit.empty()) unit = q.marginal.dimension.dimensionless() ? std::string() : q.marginal.dimension.si_unit();
    const std::string with_unit = unit.empty() ? std::string() : " " + html_text(unit);
    p << "<tr><td>" << html_text(q.name) << "</td><td class=\"text\">" << html_text(q.written) << "</td><td>"
      << study_number(q.marginal.mean() / scale - offset) << with_unit << "</td><td>" << study_number(q.marginal.standard_deviation() / scale) << with_unit
      << "</td></tr>\n";
  }
  p << "</table>\n";
  for (const OutputAnswer& o : a.outputs) {
    const std::string u = study_unit(o.column);
    p << "<h2>" << html_text(o.column.label) << (u.empty() ? "" : " [" + html_text(u) + "]") << "</h2>\n";
    if (o.moments.n == 0) {
      p << "<p>No sample has a value.</p>\n";
      continue;
    }
    // What the terminal prints, on paper too: the intervals, the quantiles, the counts beyond the
    // limits, the indices as numbers (the charts' values are only in their tooltips).
    p << "<p>n " << o.moments.n << (o.failed ? " (" + std::to_string(o.failed) + " failed)" : "") << ", "
      << html_text(moments_text(o.moments)) << "</p>\n";
    if (o.capability) p << "<p>" << html_text(capability_text(o)) << "</p>\n";
    p << histogram_svg(o);
    if (!o.quantiles.empty()) {
      p << "<table><tr><th>quantile</th><th>value</th><th>interval</th></tr>\n";
      for (const QuantileEstimate& q : o.quantiles)
        p << "<tr><td>" << study_number(q.level) << "</td><td>" << study_number(q.value) << "</td><td>" << study_interval(q.interval) << "</td></tr>\n";
      p << "</table>\n";
    }
    if (o.sobol && !o.sobol->indices.empty()) {
      p << "<h3>Sobol' indices (" << o.sobol->samples << " base samples): first order dark, total light, bootstrap intervals</h3>\n"
        << sobol_svg(spec, *o.sobol) << "<table><tr><th>parameter</th><th>first order</th><th>interval</th><th>total</th><th>interval</th></tr>\n";
      for (std::size_t j = 0; j < o.sobol->indices.size(); ++j) {
        const SobolIndex& i = o.sobol->indices[j];
        p << "<tr><td>" << html_text(spec.parameters[j].name) << "</td><td>" << study_number(i.first) << "</td><td>" << study_interval(i.first_interval)
          << "</td><td>" << study_number(i.total) << "</td><td>" << study_interval(i.total_interval) << "</td></tr>\n";
      }
      p << "</table>\n";
    }
  }
  if (!a.events.empty()) {
    p << "<h2>Events</h2>\n<table><tr><th>event</th><th>events</th><th>trials</th><th>probability</th><th>Wilson</th><th>Clopper-Pearson</th></tr>\n";
    for (const EventAnswer& e : a.events) {
      const Proportion& q = e.probability;
      p << "<tr><td>" << html_text(e.event->name) << "</td><td>" << q.events << "</td><td>" << q.trials << "</td><td>" << study_number(q.estimate)
        << "</td><td>[" << study_number(q.wilson.lower) << ", " << study_number(q.wilson.upper) << "]</td><td>[" << study_number(q.clopper_pearson.lower) << ", "
        << study_number(q.clopper_pearson.upper) << "]</td></tr>\n";
    }
    p << "</table>\n";
  }
  p << "</body></html>\n";
  return p.str();
}

}  // namespace mechgraph::cli
