#pragma once
// Results as Python sees them: a scalar a float, a series a numpy array (its axis and labels
// beside), a table a dict of numpy columns with their names and SI units (the Python package makes
// the structured array and the DataFrame). Values are copied: a result outlives the run.
#include <mechgraph/evaluator.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace mechgraph::python {

pybind11::array_t<double> to_array(const std::vector<double>& values);

/// The value of one output: float, numpy array, table dict, or for a domain object handle (a cam
/// law) the text "<kind>".
pybind11::object output_value(const OutputValue& output);

/// A table as {"axis": column, "channels": [column, ...], "histogram": bool, "closed_curve": bool,
/// "marks": [(label, si), ...]}, a column being {"name", "unit" (SI), "display_unit", "values"}.
pybind11::dict table_dict(const Table& table);

/// Text from a plugin or a scene as a Python str: bytes that are not UTF-8 (a plugin may make
/// any) become U+FFFD instead of failing the conversion with UnicodeDecodeError.
pybind11::str python_text(std::string_view text);

/// The SI unit of a dimension as results carry it ("" when dimensionless).
std::string si_unit_label(Dimension d);

}  // namespace mechgraph::python
