#pragma once
// Units that cannot slip: a number from Python for a parameter that has a dimension must say its
// unit ("9 mm", (9, "mm"), a pint quantity, a column header "lift [mm]") or be marked as SI
// (mechgraph.si(0.009), si=True). A bare 9 for a valve lift would otherwise be 9 m and run without
// a word. Dimensionless parameters (counts, ratios) take bare numbers.
#include <mechgraph/dimension.hpp>
#include <mechgraph/error_subject.hpp>
#include <mechgraph/scene.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace mechgraph::python {

/// The unit a person working with the scene thinks of `name` in: the unit the scene writes its value
/// in ("mm" for `lift: 8 mm`, and for `kurz.max_lift: $lift`), else the scene's display unit for
/// `d` (`units: { length: mm }`), else the SI unit of `d`.
std::string scene_unit(const SceneSpec& scene, std::string_view name, Dimension d);

/// What was given without a unit: one number, an array for a list parameter, a sweep's column.
enum class BareKind { number, array, column };

/// The SceneError message refusing a bare `given` for `name` of dimension `d` (not dimensionless):
/// it names the dimension, the scene's unit and SI's, and the ways to say which is meant.
std::string bare_number_refusal(const std::string& context, std::string_view name, std::string_view given, Dimension d,
                                const std::string& scene_unit, BareKind kind);

/// What a `set=` name is about, as an error carries it: "kurz.max_lift" is node kurz, parameter
/// max_lift; "rpm" (a scene parameter) parameter rpm.
ErrorSubject subject_of(std::string_view name);

/// The shortest text that reads back as `x` ("9", "0.0085").
std::string number_text(double x);

/// `values` given in `unit` ("deg"), in SI; a unit that does not parse, or of another dimension than
/// `expected`, is a SceneError naming `context`.
std::vector<double> values_in_si(const std::vector<double>& values, const std::string& unit, Dimension expected,
                                 const std::string& context);

}  // namespace mechgraph::python
