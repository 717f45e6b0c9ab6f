#include <mechgraph/knob_bench_outputs.hpp>

#include <algorithm>
#include <cmath>

namespace mechgraph {
namespace {

// One comparable piece of a node's outputs: a scalar, a series, or one channel of a table.
struct Piece {
  std::string label;            // "node.port" or "node.port:channel"
  bool scalar = false;
  Dimension dimension{};
  std::vector<double> axis;     // empty for a scalar
  std::vector<double> values;
};

std::vector<Piece> pieces_of(const std::vector<OutputValue>& outputs, const std::vector<std::string>& work_counters) {
  std::vector<Piece> pieces;
  for (const OutputValue& o : outputs) {
    const std::string port = o.label.substr(o.label.find('.') + 1);
    if (!is_compared_output(port, work_counters)) continue;
    switch (o.value.kind()) {
      case ValueKind::scalar: pieces.push_back({o.label, true, o.dimension, {}, {o.value.as_scalar()}}); break;
      case ValueKind::series:
        pieces.push_back({o.label, false, o.dimension, o.value.as_series().axis, o.value.as_series().values});
        break;
      case ValueKind::table: {
        const Table& t = o.value.as_table();
        for (const Table::Column& c : t.channels) pieces.push_back({o.label + ":" + c.name, false, c.dimension, t.axis.values, c.values});
        break;
      }
      case ValueKind::handle: break;
    }
  }
  return pieces;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// The same number of elements over the same axis (to 1e-12 of the axis' magnitude).
bool same_shape(const Piece& a, const Piece& b) {
  if (a.scalar != b.scalar || a.values.size() != b.values.size() || a.axis.size() != b.axis.size()) return false;
  const double tolerance = 1e-12 * std::max(max_abs(a.axis), max_abs(b.axis));
  for (std::size_t i = 0; i < a.axis.size(); ++i)
    if (!(std::abs(a.axis[i] - b.axis[i]) <= tolerance)) return false;
  return true;
}

// The floor of each scalar: a thousandth of the largest magnitude among the scalars of its dimension.
double scalar_floor(const std::vector<Piece>& reference, const Dimension& d) {
  double scale = 0.0;
  for (const Piece& p : reference)
    if (p.scalar && p.dimension == d) scale = std::max(scale, std::abs(p.values[0]));
  return 1e-3 * scale;
}

// |deviation| / scale, where a scale of zero (a reference that is zero everywhere) makes any
// deviation 100 %, and none 0.
double relative(double deviation, double scale) {
  if (!(scale > 0.0)) return deviation == 0.0 ? 0.0 : 1.0;
  return std::abs(deviation) / scale;
}

void record(OutputDeviation& out, const std::string& label, double e) {
  ++out.compared;
  double& per_output = out.per_output[label];
  per_output = std::max(per_output, e);
  if (e > out.max_relative || out.worst.empty()) {
    out.max_relative = std::max(out.max_relative, e);
    out.worst = label;
  }
}

}  // namespace

bool is_compared_output(std::string_view port, const std::vector<std::string>& work_counters) {
  if (std::find(work_counters.begin(), work_counters.end(), port) != work_counters.end()) return false;
  constexpr std::string_view uncertainty = "_error";
  return !(port.size() > uncertainty.size() && port.substr(port.size() - uncertainty.size()) == uncertainty);
}

OutputDeviation relative_difference(const std::vector<OutputValue>& trial, const std::vector<OutputValue>& reference,
                                    const std::vector<std::string>& work_counters) {
  OutputDeviation out;
  const std::vector<Piece> tried = pieces_of(trial, work_counters);
  const std::vector<Piece> refs = pieces_of(reference, work_counters);
  for (const Piece& t : tried) {
    const auto r = std::find_if(refs.begin(), refs.end(), [&](const Piece& p) { return p.label == t.label; });
    if (r == refs.end() || !same_shape(t, *r)) continue;
    const double group_scale = r->scalar ? scalar_floor(refs, r->dimension) : max_abs(r->values);
    for (std::size_t i = 0; i < t.values.size(); ++i)
      record(out, t.label, relative(t.values[i] - r->values[i], std::max(r->scalar ? std::abs(r->values[i]) : 0.0, group_scale)));
  }
  return out;
}

OutputDeviation relative_spread(const std::vector<std::vector<OutputValue>>& runs, const std::vector<std::string>& work_counters) {
  OutputDeviation out;
  if (runs.size() < 2) return out;
  std::vector<std::vector<Piece>> pieces;
  for (const auto& run : runs) pieces.push_back(pieces_of(run, work_counters));
  // The pieces every run has in the same shape, with their means and standard deviations.
  struct Moments {
    Piece mean;
    std::vector<double> deviation;
  };
  std::vector<Moments> moments;
  const double k = static_cast<double>(runs.size());
  for (const Piece& first : pieces[0]) {
    std::vector<const Piece*> same;
    for (const auto& run : pieces) {
      const auto p = std::find_if(run.begin(), run.end(), [&](const Piece& q) { return q.label == first.label; });
      if (p == run.end() || !same_shape(first, *p)) break;
      same.push_back(&*p);
    }
    if (same.size() != runs.size()) continue;
    Moments m{first, std::vector<double>(first.values.size(), 0.0)};
    for (std::size_t i = 0; i < first.values.size(); ++i) {
      double sum = 0.0;
      bool all_equal = true;
      for (const Piece* p : same) {
        sum += p->values[i];
        all_equal = all_equal && p->values[i] == first.values[i];
      }
      if (all_equal) continue;  // a value the seed does not touch: no spread (not a rounding's worth)
      const double mean = sum / k;
      double squares = 0.0;
      for (const Piece* p : same) squares += (p->values[i] - mean) * (p->values[i] - mean);
      m.mean.values[i] = mean;
      m.deviation[i] = std::sqrt(squares / (k - 1.0));
    }
    moments.push_back(std::move(m));
  }
  std::vector<Piece> means;
  for (const Moments& m : moments) means.push_back(m.mean);
  for (const Moments& m : moments) {
    const double group_scale = m.mean.scalar ? scalar_floor(means, m.mean.dimension) : max_abs(m.mean.values);
    for (std::size_t i = 0; i < m.deviation.size(); ++i)
      record(out, m.mean.label, relative(m.deviation[i], std::max(m.mean.scalar ? std::abs(m.mean.values[i]) : 0.0, group_scale)));
  }
  return out;
}

bool bit_identical(const std::vector<OutputValue>& a, const std::vector<OutputValue>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Value& x = a[i].value;
    const Value& y = b[i].value;
    if (a[i].label != b[i].label || x.kind() != y.kind()) return false;
    switch (x.kind()) {
      case ValueKind::scalar:
        if (!(x.as_scalar() == y.as_scalar())) return false;
        break;
      case ValueKind::series:
        if (x.as_series().axis != y.as_series().axis || x.as_series().values != y.as_series().values) return false;
        break;
      case ValueKind::table: {
        const Table& s = x.as_table();
        const Table& t = y.as_table();
        if (s.axis.values != t.axis.values || s.channels.size() != t.channels.size()) return false;
        for (std::size_t c = 0; c < s.channels.size(); ++c)
          if (s.channels[c].name != t.channels[c].name || s.channels[c].values != t.channels[c].values) return false;
        break;
      }
      case ValueKind::handle: break;
    }
  }
  return true;
}

}  // namespace mechgraph
