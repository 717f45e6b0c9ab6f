#include "python_values.hpp"

#include "case_values.hpp"

#include <mechgraph/errors.hpp>

#include <pybind11/numpy.h>

namespace mechgraph::python {
namespace py = pybind11;

namespace {

std::string type_name(py::handle value) { return py::str(py::type::of(value).attr("__name__")); }

// numpy's one-letter kind of the dtype of `value` (a numpy scalar or array, a pandas Series), or 0
// when it has none.
char dtype_kind(py::handle value) {
  try {
    if (!py::hasattr(value, "dtype")) return 0;
    const py::object dtype = value.attr("dtype");
    if (!py::hasattr(dtype, "kind")) return 0;
    const std::string kind = py::str(dtype.attr("kind"));
    return kind.size() == 1 ? kind[0] : 0;
  } catch (const py::error_already_set&) {
    return 0;
  }
}

// Why values of numpy kind `kind` are refused, or nullptr for numbers ('i', 'u', 'f'), text ('U')
// and objects ('O', looked at one by one).
const char* refusal(char kind) {
  switch (kind) {
    case 'b': return "True/False is not a value (give a number in SI or text with its unit)";
    case 'c': return "a complex number is not a value (its imaginary part would be lost)";
    case 'M': return "a date or time is not a value (it would be read as nanoseconds since 1970)";
    case 'm': return "a duration (timedelta) is not a value (it would be read as nanoseconds); give text with its unit ('2.5 ms')";
    case 'S': return "bytes are not text (decode them to str)";
    case 'V': return "a structured value is not a value";
    default: return nullptr;
  }
}

// The kind (as numpy names it) of a date, time or duration from Python's datetime module (pandas'
// Timestamp and Timedelta derive from them), or 0.
char datetime_kind(py::handle value) {
  const py::module_ datetime = py::module_::import("datetime");
  if (py::isinstance(value, datetime.attr("timedelta"))) return 'm';
  if (py::isinstance(value, datetime.attr("date")) || py::isinstance(value, datetime.attr("time"))) return 'M';
  return 0;
}

[[noreturn]] void refuse(const std::string& context, const std::string& why) { throw SceneError(context + ": " + why); }

}  // namespace

ScalarValue scalar_value(py::handle value, const std::string& context) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (PyBool_Check(value.ptr())) refuse(context, refusal('b'));
  if (PyFloat_Check(value.ptr()) || PyLong_Check(value.ptr())) {  // float, int, numpy.float64
    try {
      return py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
    } catch (const py::error_already_set&) {
      refuse(context, "the integer is too large for a number (" + std::string(py::str(value)).substr(0, 40) + "...)");
    }
  }
  const char kind = dtype_kind(value);  // numpy scalars and 0-d arrays
  if (const char* why = refusal(kind)) refuse(context, why);
  if (py::isinstance<py::array>(value) && py::array(py::reinterpret_borrow<py::object>(value)).ndim() != 0)
    refuse(context, "an array where one value was expected");
  if ((kind == 'U' || kind == 'O') && py::isinstance<py::array>(value)) return scalar_value(value.attr("item")(), context);
  if (value.is_none()) refuse(context, "None is not a value");
  if (PyBytes_Check(value.ptr()) || PyByteArray_Check(value.ptr())) refuse(context, refusal('S'));
  if (PyComplex_Check(value.ptr())) refuse(context, refusal('c'));
  if (const char dt = datetime_kind(value)) refuse(context, refusal(dt));
  if (kind == 'i' || kind == 'u' || kind == 'f' || py::hasattr(value, "__float__")) {  // numpy numbers, Decimal, Fraction
    try {
      return py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
    } catch (const py::error_already_set& e) {
      refuse(context, type_name(value) + " is not a number (" + std::string(e.what()).substr(0, 120) + ")");
    }
  }
  refuse(context, "expected text with its unit ('6500 rpm') or a number in SI, got " + type_name(value));
}

bool is_sequence(py::handle value) {
  if (py::isinstance<py::str>(value) || PyBytes_Check(value.ptr())) return false;  // numpy.str_ has a length too
  if (py::isinstance<py::array>(value)) return py::array(py::reinterpret_borrow<py::object>(value)).ndim() > 0;
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) return true;
  return dtype_kind(value) != 0 && py::hasattr(value, "__len__");  // a pandas Series
}

ColumnValues column_values(py::handle values, const std::string& context) {
  if (const char* why = refusal(dtype_kind(values))) refuse(context, why);  // the column as a whole
  py::object sequence = py::reinterpret_borrow<py::object>(values);
  if (!py::isinstance<py::list>(sequence) && !py::isinstance<py::tuple>(sequence) && !py::isinstance<py::array>(sequence))
    sequence = py::module_::import("numpy").attr("asarray")(sequence);  // a pandas Series, a range, ...
  ColumnValues out;
  if (py::isinstance<py::array>(sequence)) {
    const py::array array(sequence);
    if (array.ndim() != 1)
      refuse(context, "expected a one-dimensional sequence of values, got " + std::to_string(array.ndim()) + " dimensions");
    const char kind = array.dtype().kind();
    if (const char* why = refusal(kind)) refuse(context, why);
    if (kind == 'i' || kind == 'u' || kind == 'f') {
      const auto numbers = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
      out.numbers.assign(numbers.data(), numbers.data() + numbers.size());
      return out;
    }
    sequence = array.attr("tolist")();  // text, or objects one by one
  }
  const py::sequence cells(sequence);
  const std::size_t n = py::len(cells);
  std::vector<ScalarValue> each;
  each.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    each.push_back(scalar_value(cells[i], context + ", row " + std::to_string(i)));
    out.text = out.text || std::holds_alternative<std::string>(each.back());
  }
  if (out.text) {
    out.cells.reserve(n);
    for (ScalarValue& v : each)
      out.cells.push_back(std::holds_alternative<std::string>(v) ? std::move(std::get<std::string>(v))
                                                                 : si_text(std::get<double>(v), Dimension{}));
  } else {
    out.numbers.reserve(n);
    for (const ScalarValue& v : each) out.numbers.push_back(std::get<double>(v));
  }
  return out;
}

}  // namespace mechgraph::python
