#pragma once
// The cases of a sweep: which parameters vary (by the name `--set` uses: `rpm` for a scene
// parameter, `cam.max_lift` for a node's) and the value each takes in each case. Three ways to
// make them: a full grid (`--vary`), a table read from CSV (`--cases`) and a Latin hypercube
// sample (`--sample`, reproducible from its seed).
#include <mechgraph/dimension.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace mechgraph {

/// One value of one case: a number with its dimension (SI), or a word (a choice such as an
/// integrator's name) for parameters that take one.
struct CaseValue {
  std::string text;                // as written, or made from the number
  std::optional<double> si;        // when it is a number
  Dimension dimension;             // of the number
};

struct SweepVariable {
  std::string name;  // "rpm", "cam.max_lift"
  std::string unit;  // the unit its values are shown in ("" = SI, or a word)
};

struct CaseTable {
  std::vector<SweepVariable> variables;
  std::vector<std::vector<CaseValue>> cases;  // cases[i][v]: variable v in case i
  std::string origin;                         // "--vary ...", "FILE.csv", "--sample ... --seed S"

  /// The value of variable v in case i as the output shows it (in the variable's unit).
  std::string shown(std::size_t i, std::size_t v) const;
};

/// `NAME=FROM:TO:N` (units in FROM and TO as in scenes, TO may omit it; N >= 1 points, ends
/// included) or `NAME=A,B,C` (the values listed, numbers with units or words).
struct VarySpec {
  std::string name;
  std::vector<CaseValue> values;
  std::string unit;
};
VarySpec parse_vary(std::string_view text);

/// The full grid of the specs; the last one varies fastest.
CaseTable make_grid(const std::vector<VarySpec>& specs);

/// `NAME=LO:HI` for a Latin hypercube sample.
struct SampleSpec {
  std::string name;
  double low = 0.0, high = 0.0;  // SI
  Dimension dimension;
  std::string unit;
};
SampleSpec parse_sample(std::string_view text);

/// n cases, each variable's range cut in n equal strata with one point in each, strata paired at
/// random: the same (specs, n, seed) give the same cases on every machine (splitmix64 + own
/// shuffle, nothing implementation-defined).
CaseTable make_latin_hypercube(const std::vector<SampleSpec>& specs, std::size_t n, std::uint64_t seed);

/// A CSV file of cases: a header of parameter names (`name` or `name [unit]`), then one case per
/// row; a cell is a number with its unit (`5600 rpm`), a bare number in the header's unit, or a
/// word. Blank lines and lines starting with '#' are skipped. Throws SceneError "file:line:column".
CaseTable read_cases_csv(const std::filesystem::path& file);

}  // namespace mechgraph
