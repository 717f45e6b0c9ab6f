#pragma once
// The one place where a Python object becomes a value mechgraph reads: a `set=` entry, a cell of a
// sweep's column, an element of an array for a list parameter. Everything that takes values from
// Python goes through scalar_value or column_values, so every kind is accepted or refused the
// same way wherever it is given.
//
// Accepted: text (str, numpy.str_: "6500 rpm", a word), numbers (int, float, numpy integers and
// floats, anything else with __float__ such as Decimal or Fraction), and for a column or an array
// one-dimensional sequences of those (numpy arrays, lists, tuples, pandas Series).
// Refused with a SceneError naming where the value was given:
//   - bool-likes: True/False, numpy.bool_, bool arrays (True is not a length of 1 m);
//   - complex numbers and arrays (the imaginary part would be lost);
//   - dates, times and durations: datetime, date, time, timedelta, numpy datetime64/timedelta64,
//     pandas Timestamp/Timedelta and their columns (they would be read as nanoseconds);
//   - bytes, None, pandas NA/NaT, structured arrays, anything else.
#include <pybind11/pybind11.h>

#include <string>
#include <variant>
#include <vector>

namespace mechgraph::python {

/// One value: text, or a number (in SI, or in a column's unit).
using ScalarValue = std::variant<std::string, double>;

/// `value` as one value; any refused kind is a SceneError naming `context` and the kind.
ScalarValue scalar_value(pybind11::handle value, const std::string& context);

/// Whether `value` is given as a sequence of values (a numpy array of one or more dimensions, a
/// list, a tuple, a pandas Series) rather than as one value.
bool is_sequence(pybind11::handle value);

/// A one-dimensional sequence of values: all numbers, or text cells when any cell is text (the
/// numbers among them written as text, "0.5").
struct ColumnValues {
  bool text = false;
  std::vector<double> numbers;     // when !text
  std::vector<std::string> cells;  // when text
  std::size_t size() const { return text ? cells.size() : numbers.size(); }
};

/// `values` cell by cell through the rules of scalar_value (a numpy array of numbers at once);
/// a refused kind is a SceneError naming `context` (and the row, for one cell).
ColumnValues column_values(pybind11::handle values, const std::string& context);

}  // namespace mechgraph::python
