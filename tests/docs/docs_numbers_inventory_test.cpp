// Every number with a unit in the method notes (docs/methods/*.md), in docs/*.md and in the README's
// prose (outside fenced blocks: the README's output listings are compared line by line with what
// the commands print, docs_numbers_readme_test.cpp) is classified here: recomputed
// by a named test of tests/docs, or an input of the example, a default value, a constant of the
// method, a citation, a measurement (a time on the project's machine, not reproducible in a test),
// a figure from before a fix (historical), a bound a test asserts, or a symbol in a formula. A
// number added to a note without a line here fails, and so does a line whose text the note no
// longer has, or whose recomputing test does not exist. Results are recomputed where the test
// names say; this table only keeps the count honest.
#include "docs/doc_numbers.hpp"

#include <filesystem>
#include <map>

using namespace mechgraph::testing::docs;

namespace {

enum class Kind { recomputed, input, default_value, method_constant, citation, measured, historical, checked_bound, formula };

struct Entry {
  const char* file;  // relative to the source tree
  const char* text;  // the doc's words around the number(s), as they read with line breaks made spaces
  Kind kind;
  const char* why;   // for recomputed: the name of the test case that recomputes it
};

// clang-format off
const Entry inventory[] = {
#include "docs/docs_numbers_inventory.inc"
};
// clang-format on

const char* const documents[] = {"docs/methods/backlash.md", "docs/methods/followers.md", "docs/methods/numerics.md",
                                 "docs/methods/uncertainty.md", "docs/methods/valvetrain.md", "README.md", "docs/bench.md",
                                 "docs/peers.md", "docs/python.md", "docs/reports.md", "docs/scenes.md", "docs/sweeps.md",
                                 "docs/writing-plugins.md"};

// The document's prose: fenced blocks blanked, line breaks made spaces, runs of spaces made one.
std::string prose_text(const std::string& relative) {
  std::istringstream in(doc_file(relative));
  std::string text;
  bool fenced = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("```", 0) == 0) {
      fenced = !fenced;
      line.clear();
    }
    text += (fenced ? std::string() : line) + " ";
  }
  return std::regex_replace(text, std::regex(" +"), " ");
}

// A number or a range followed by a unit, as the notes print results: "4.63 mm", "17 %",
// "0.4-1.6 %"; "3.5e15" is not one (no unit): such numbers are recomputed where they are results
// without being counted here. The character before the number must not belong to a word, a number,
// an exponent or a ratio.
const std::regex number_with_unit(
    "(^|[^A-Za-z0-9_.^/-])([-+]?[0-9]+(?:\\.[0-9]+)?(?:e[-+]?[0-9]+)?)(?:-[0-9]+(?:\\.[0-9]+)?(?:e[-+]?[0-9]+)?)? ?"
    "(mm\\^2\\*deg|mm\\^2\\*s|mm/deg\\^2|N/mm|kN/mm|m/s\\^2|m/s|MPa|GPa|mm|um|deg|rad|rpm|ms|us|s|%|arcmin|Hz|N|ppm|MiB|KiB|GiB|MB|m)"
    "(?![A-Za-z0-9_/^*])");

std::string all_doc_test_sources() {
  std::string all;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(MECHGRAPH_SOURCE_DIR) + "/tests/docs"))
    if (entry.path().extension() == ".cpp") all += doc_file("tests/docs/" + entry.path().filename().string());
  return all;
}

}  // namespace

TEST_CASE("docs: every number with a unit in docs/ and the README's prose is recomputed or classified", "[docs][inventory]") {
  const std::string sources = all_doc_test_sources();
  std::map<Kind, int> counted;
  int found = 0;
  for (const char* note : documents) {
    const std::string doc = prose_text(note);
      for (const Entry& e : inventory) {
      if (std::string(e.file) != note) continue;
      const std::string text = e.text;
      INFO(note << ": the inventory's text is no longer in the note: " << text);
      CHECK(doc.find(text) != std::string::npos);
      if (e.kind == Kind::recomputed) {
        INFO(note << ": \"" << text << "\" is said to be recomputed by a test case that does not exist: " << e.why);
        CHECK(sources.find("TEST_CASE(\"" + std::string(e.why) + "\"") != std::string::npos);
      }
    }
    for (auto it = std::sregex_iterator(doc.begin(), doc.end(), number_with_unit); it != std::sregex_iterator(); ++it) {
      const std::size_t at = static_cast<std::size_t>(it->position(2));
      ++found;
      const Entry* covering = nullptr;
      for (const Entry& e : inventory) {
        if (std::string(e.file) != note) continue;
        for (std::size_t s = doc.find(e.text); s != std::string::npos && !covering; s = doc.find(e.text, s + 1))
          if (s <= at && at < s + std::string(e.text).size()) covering = &e;
        if (covering) break;
      }
      const std::size_t from = at < 60 ? 0 : at - 60;
      INFO(note << ": a number no test recomputes and no line of the inventory classifies (add it to "
                   "tests/docs/docs_numbers_inventory.inc): ..."
                << doc.substr(from, at - from + 30) << "...");
      CHECK(covering != nullptr);
      if (covering) ++counted[covering->kind];
    }
  }
  // The count (shown with -s).
  INFO("docs: " << found << " numbers with units; recomputed " << counted[Kind::recomputed] << ", inputs " << counted[Kind::input]
                        << ", defaults " << counted[Kind::default_value] << ", constants " << counted[Kind::method_constant] << ", citations "
                        << counted[Kind::citation] << ", measured " << counted[Kind::measured] << ", historical " << counted[Kind::historical]
                        << ", bounds " << counted[Kind::checked_bound] << ", formula symbols " << counted[Kind::formula]);
  CHECK(found > 0);
}

TEST_CASE("docs: every output listing (a fenced block without a language) is compared with the tool or exempt", "[docs][inventory]") {
  // The first line of each such block, and what holds it to the tool (a test case of tests/docs
  // that compares it line by line) or why it holds no result. A new listing fails here until it
  // is one or the other; blocks with a language are commands (sh), scenes (yaml), code (cpp,
  // cmake) or Python that python/tests/test_snippets.py runs.
  const std::vector<std::pair<std::string, std::string>> known = {
      {"Three cams of equal tappet lift", "docs: README's valve-train study listing is what run-study.sh and run print"},
      {"Kurz cam, spring for 5600 rpm", "docs: README's valve dynamics listing is what run prints"},
      {"Free play of each hinge along the rod", "docs: README's backlash listing and provenance excerpt are what run prints"},
      {"v.opening_angle [deg (cam)]: n 128", "docs: README's uncertainty study listing is what study prints"},
      {"One lift law, two followers", "docs: README's contour listing, its note and the events CSV are what run writes"},
      {"flat: contour: the cam turns", "docs: README's contour listing, its note and the events CSV are what run writes"},
      {"checking_lift [mm],opening [deg (cam)]", "docs: README's contour listing, its note and the events CSV are what run writes"},
      {"v_kurz: intake: opens", "docs: README's valve-train study listing is what run-study.sh and run print"},
      {"\"provenance\": {", "docs: README's backlash listing and provenance excerpt are what run prints"},
      {"Roller finger follower", "docs: README's finger-follower listing is what run prints"},
      {"elastic (valvetrain.dynamics) knob tolerance", "docs: bench.md, the tolerance listing and the integrators' floor on the elastic drive"},
      {"sdk/include/mechgraph/", ""},               // README: the source tree's layout
      {"bench/peers/run.sh [--quick]", ""},          // peers.md: a usage synopsis
      {"/usr/bin/python3 bench/peers/side_by_side.py", ""},  // peers.md: a usage synopsis
      {"mechgraph sweep SCENE (--vary", ""},         // sweeps.md: a usage synopsis
      {"plugin '.../mechgraph_foreign.so'", ""},     // writing-plugins.md: an error message's wording
      {"fixed part -> hinge 1", ""},                 // backlash.md: the chain as a diagram
  };
  const std::string sources = all_doc_test_sources();
  for (const auto& [first, test] : known)
    if (!test.empty()) {
      INFO("the listing \"" << first << "\" is said to be compared by a test case that does not exist: " << test);
      CHECK(sources.find("TEST_CASE(\"" + test + "\"") != std::string::npos);
    }
  for (const char* document : documents) {
    std::istringstream in(doc_file(document));
    bool fenced = false, first = false;
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("```", 0) == 0) {
        fenced = !fenced;
        first = fenced && line == "```";
        continue;
      }
      if (!first) continue;
      first = false;
      bool listed = false;
      for (const auto& k : known) listed = listed || line.rfind(k.first, 0) == 0;
      INFO(document << ": an output listing that no test compares with the tool (add its check to tests/docs and its first "
                       "line to this list): "
                    << line);
      CHECK(listed);
    }
  }
}
