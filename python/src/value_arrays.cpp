#include "value_arrays.hpp"

#include <mechgraph/text_escape.hpp>

#include <algorithm>

namespace mechgraph::python {
namespace py = pybind11;

py::array_t<double> to_array(const std::vector<double>& values) {
  py::array_t<double> out(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

py::str python_text(std::string_view text) { return py::str(utf8_sanitized(text)); }

std::string si_unit_label(Dimension d) { return d.dimensionless() ? std::string() : d.si_unit(); }

namespace {

py::dict column_dict(const Table::Column& c) {
  py::dict d;
  d["name"] = python_text(c.name);
  d["unit"] = si_unit_label(c.dimension);
  d["display_unit"] = python_text(c.display_unit);
  d["values"] = to_array(c.values);
  return d;
}

}  // namespace

py::dict table_dict(const Table& table) {
  py::dict d;
  d["axis"] = column_dict(table.axis);
  py::list channels;
  for (const Table::Column& c : table.channels) channels.append(column_dict(c));
  d["channels"] = channels;
  d["histogram"] = table.histogram;
  d["closed_curve"] = table.closed_curve;
  py::list marks;
  for (const Table::Mark& m : table.axis_marks) marks.append(py::make_tuple(python_text(m.label), m.value));
  d["marks"] = marks;
  return d;
}

py::object output_value(const OutputValue& output) {
  const Value& v = output.value;
  switch (v.kind()) {
    case ValueKind::scalar: return py::float_(v.as_scalar());
    case ValueKind::series: return to_array(v.as_series().values);
    case ValueKind::table: return table_dict(v.as_table());
    case ValueKind::handle: return python_text("<" + std::string(v.as_handle()->kind()) + ">");
  }
  return py::none();
}

}  // namespace mechgraph::python
