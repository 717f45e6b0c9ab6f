#pragma once
// Values from Python for a scene's parameters, made the way the command line makes them: text with
// its unit ("6500 rpm", read like a `--set` or a cases-file cell) or a number in SI. A number in SI
// takes the dimension of the parameter it reaches (a scene parameter: the first node parameter
// written `$name`), so 680.7 for `rpm` is 680.7 rad/s and 0.009 for `cam.max_lift` is 9 mm.
#include <mechgraph/graph.hpp>
#include <mechgraph/sweep/case_table.hpp>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph::python {

/// The dimension of what `name` sets (`rpm`, `cam.max_lift`; a list parameter: of its elements),
/// or none for an unknown name or a value inside a record (the case binder then names the problem).
std::optional<Dimension> target_dimension(const Graph& graph, std::string_view name);

/// A number that parses back to the same double, with the SI unit of `d` ("0.0090000000000000011 m").
std::string si_text(double si, Dimension d);

/// `text` as one YAML double-quoted scalar that reads back as exactly `text` (for the places that
/// take YAML: an override): '"' and '\\' escaped, C0, DEL and C1 controls as escapes.
std::string yaml_quoted(std::string_view text);

/// "6500 rpm" (or a word such as "roller"), read as a cases file's cell is; a non-finite number is
/// a SceneError naming `context`.
CaseValue value_from_text(const std::string& text, const std::string& context);

/// A number in SI for a parameter of dimension `d`; non-finite is a SceneError naming `context`.
CaseValue value_from_si(double si, Dimension d, const std::string& context);

}  // namespace mechgraph::python
