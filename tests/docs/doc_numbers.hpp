#pragma once
// Reading the numbers docs/ quotes, for the tests that recompute them (tests/docs/*_test.cpp).
//
// A number in a doc is held to what the tool computes at the digits the doc prints: "4.63 mm"
// admits 4.625 .. 4.635 mm, "17 %" 16.5 .. 17.5 %. A sentence is found by a pattern that captures
// its numbers, so rewording it, or changing a number on either side, fails the test that quotes it.
// Output blocks (the README's terminal listings) are compared line by line with what the command
// prints now.
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace mechgraph::testing::docs {

/// The file `relative` (to the source tree) as it is.
inline std::string doc_file(const std::string& relative) {
  std::ifstream in(std::string(MECHGRAPH_SOURCE_DIR) + "/" + relative);
  REQUIRE(in);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// The doc's text with its line breaks made spaces and runs of spaces made one, so that a pattern
/// may span lines.
inline std::string doc_text(const std::string& relative) {
  std::string text = doc_file(relative);
  for (char& c : text)
    if (c == '\n') c = ' ';
  return std::regex_replace(text, std::regex(" +"), " ");
}

/// The groups `pattern` captures in `doc` (the first match); the test stops when the doc no longer
/// says it.
inline std::vector<std::string> quoted(const std::string& doc, const std::string& pattern) {
  std::smatch m;
  INFO("the doc no longer says: " << pattern);
  REQUIRE(std::regex_search(doc, m, std::regex(pattern)));
  std::vector<std::string> groups;
  for (std::size_t i = 1; i < m.size(); ++i) groups.push_back(m[i].str());
  return groups;
}

/// "node.port" as a scene's output.
inline PortRef port_ref(const std::string& label) {
  PortRef ref;
  ref.node = label.substr(0, label.find('.'));
  ref.port = label.substr(label.find('.') + 1);
  return ref;
}

/// The pattern of a number as docs print it (sign, digits, decimals, exponent); one capture group.
inline const char* const number = "([-+]?[0-9]+(?:\\.[0-9]+)?(?:e[-+]?[0-9]+)?)";

/// Half a unit of the last digit `text` prints: 0.005 for "4.63", 0.5 for "17", 5e8 for "6.2e15".
inline double half_unit(const std::string& text) {
  const std::size_t e = text.find_first_of("eE");
  const std::string mantissa = text.substr(0, e);
  const int exponent = e == std::string::npos ? 0 : std::stoi(text.substr(e + 1));
  const std::size_t dot = mantissa.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(mantissa.size() - dot - 1);
  return 0.5 * std::pow(10.0, exponent - decimals);
}

/// Whether `value` (in the doc's unit) prints as `text` at the digits `text` has: within half a
/// unit of its last digit (and a rounding unit of slack for values that sit on the half).
inline bool rounds_to(const std::string& text, double value) {
  const double printed = std::stod(text);
  return std::isfinite(value) && std::abs(value - printed) <= half_unit(text) * (1 + 1e-9) + 1e-12 * std::abs(printed);
}

/// CHECKs that the doc's `text` is `value` at its printed digits, naming what it is.
inline void check_quote(const std::string& what, const std::string& text, double value) {
  INFO(what << ": the doc says " << text << ", the tool gives " << value);
  CHECK(rounds_to(text, value));
}

/// CHECKs a figure the doc gives as "about": within `relative` of `value`.
inline void check_about(const std::string& what, const std::string& text, double value, double relative) {
  INFO(what << ": the doc says about " << text << ", the tool gives " << value);
  CHECK(std::abs(std::stod(text) - value) <= relative * std::abs(value));
}

/// A file a test writes into the temporary folder (a lift table, say), removed when it goes.
class TempFile {
 public:
  TempFile(const std::string& name, const std::string& content)
      : path_((std::filesystem::temp_directory_path() / ("mechgraph_docs_test_" + std::to_string(::getpid()) + "_" + name)).string()) {
    std::ofstream out(path_);
    out << content;
    REQUIRE(out.good());
  }
  ~TempFile() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// ---- Output blocks ------------------------------------------------------------------------------

/// The fenced block of `relative` whose first line begins with `first_line` (the fences excluded).
inline std::string fenced_block(const std::string& relative, const std::string& first_line) {
  std::istringstream in(doc_file(relative));
  std::string line, block;
  bool in_fence = false, taking = false, first = false;
  while (std::getline(in, line)) {
    if (line.rfind("```", 0) == 0) {
      if (taking) return block;
      in_fence = !in_fence;
      first = in_fence;
      continue;
    }
    if (in_fence && first) {
      taking = line.rfind(first_line, 0) == 0;
      first = false;
    }
    if (taking) block += line + "\n";
  }
  INFO("no fenced block of " << relative << " begins with: " << first_line);
  REQUIRE(false);
  return {};
}

/// A line cut into its numbers and the rest (the skeleton: each number a '#', blanks made one).
struct LineShape {
  std::string skeleton;
  std::vector<std::string> numbers;
};

inline LineShape line_shape(const std::string& line) {
  static const std::regex token("(^|[\\s(\\[,=:{])([-+]?(?:[0-9]+\\.?[0-9]*|\\.[0-9]+)(?:e[-+]?[0-9]+)?)(?=$|[\\s)\\],;:}%])");
  LineShape shape;
  std::string rest;
  auto begin = std::sregex_iterator(line.begin(), line.end(), token);
  std::size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    rest += line.substr(last, m.position(2) - last) + "#";
    shape.numbers.push_back(m[2].str());
    last = m.position(2) + m.length(2);
  }
  rest += line.substr(last);
  shape.skeleton = std::regex_replace(rest, std::regex("\\s+"), " ");
  while (!shape.skeleton.empty() && shape.skeleton.back() == ' ') shape.skeleton.pop_back();
  while (!shape.skeleton.empty() && shape.skeleton.front() == ' ') shape.skeleton.erase(0, 1);
  return shape;
}

/// Whether two printed numbers are the same figure: equal within the coarser one's last digit (the
/// doc may print fewer digits than the tool, and a platform may differ in the last one). A doc's
/// bare 0 is an exact zero.
inline bool same_figure(const std::string& doc, const std::string& tool) {
  const double d = std::stod(doc), t = std::stod(tool);
  if (d == 0.0) return std::abs(t) <= 1e-12;
  return std::abs(d - t) <= 2 * std::max(half_unit(doc), half_unit(tool)) * (1 + 1e-9);
}

/// The lines of a doc's output block that the command's `output` does not print, each with the
/// nearest line of the same shape when there is one. Lines of the block are looked for in order;
/// a line beginning with "..." stands for lines left out, one ending in " ..." for the rest of
/// that line.
inline std::vector<std::string> block_mismatches(const std::string& block, const std::string& output) {
  std::vector<LineShape> printed;
  std::vector<std::string> printed_text;
  {
    std::istringstream in(output);
    for (std::string line; std::getline(in, line);) {
      printed.push_back(line_shape(line));
      printed_text.push_back(line);
    }
  }
  std::vector<std::string> problems;
  std::size_t at = 0;
  std::istringstream in(block);
  for (std::string line; std::getline(in, line);) {
    const std::size_t text = line.find_first_not_of(' ');
    if (text == std::string::npos || line.compare(text, 3, "...") == 0) continue;
    const bool rest_left_out = line.size() >= 4 && line.compare(line.size() - 4, 4, " ...") == 0;
    const LineShape want = line_shape(rest_left_out ? line.substr(0, line.size() - 4) : line);
    auto same_shape = [&](const LineShape& p) {
      if (!rest_left_out) return p.skeleton == want.skeleton && p.numbers.size() == want.numbers.size();
      return p.skeleton.compare(0, want.skeleton.size(), want.skeleton) == 0 && p.numbers.size() >= want.numbers.size();
    };
    std::size_t found = printed.size(), near = printed.size();
    for (std::size_t i = at; i < printed.size() && found == printed.size(); ++i) {
      if (!same_shape(printed[i])) continue;
      if (near == printed.size()) near = i;
      bool same = true;
      for (std::size_t k = 0; k < want.numbers.size() && same; ++k) same = same_figure(want.numbers[k], printed[i].numbers[k]);
      if (same) found = i;
    }
    if (found < printed.size()) {
      at = found + 1;
      continue;
    }
    problems.push_back("doc:  " + line + "\n  tool: " + (near < printed.size() ? printed_text[near] : std::string("(no line of this shape)")));
  }
  return problems;
}

/// CHECKs that every line of the block of `relative` beginning with `first_line` is printed by the
/// command (in `output`) with the same figures.
inline void check_block(const std::string& relative, const std::string& first_line, const std::string& output) {
  const std::vector<std::string> problems = block_mismatches(fenced_block(relative, first_line), output);
  std::string all;
  for (const std::string& p : problems) all += p + "\n";
  INFO(relative << ", the block that begins \"" << first_line << "\": lines the tool no longer prints so:\n" << all);
  CHECK(problems.empty());
}

}  // namespace mechgraph::testing::docs
