#include <mechgraph/value.hpp>

#include <cmath>

namespace mechgraph {

bool all_finite(const Value& v) {
  auto finite = [](const std::vector<double>& xs) {
    for (double x : xs)
      if (!std::isfinite(x)) return false;
    return true;
  };
  switch (v.kind()) {
    case ValueKind::scalar: return std::isfinite(v.as_scalar());
    case ValueKind::series: return finite(v.as_series().values) && finite(v.as_series().axis);
    case ValueKind::table:
      if (!finite(v.as_table().axis.values)) return false;
      for (const Table::Column& c : v.as_table().channels)
        if (!finite(c.values)) return false;
      // Axis marks are drawn by the report like any other number.
      for (const Table::Mark& m : v.as_table().axis_marks)
        if (!std::isfinite(m.value)) return false;
      return true;
    case ValueKind::handle: return true;
  }
  return true;
}

std::string_view to_string(ValueKind kind) {
  switch (kind) {
    case ValueKind::scalar: return "scalar";
    case ValueKind::series: return "series";
    case ValueKind::handle: return "handle";
    case ValueKind::table: return "table";
  }
  return "?";
}

}  // namespace mechgraph
