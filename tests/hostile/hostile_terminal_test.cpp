// Issue 28, class 7: no text from a scene, a cases file, the command line or a plugin reaches the
// terminal as a control sequence. Every command that prints text runs on a scene full of hostile
// titles, labels, notes and names, through a plugin whose summary, docs, choices, labels, notes,
// log messages and errors hold ESC, OSC (sets the window title), CSI as a C1 control (U+009B, and
// the raw byte 0x9B) and a bidi override; stdout and stderr must hold none of them.
#include "hostile/hostile_support.hpp"

#include <mechgraph/bounded_read.hpp>
#include <mechgraph/text_escape.hpp>

#include <catch2/catch.hpp>

#include <cstdio>

using Catch::Matchers::Contains;
using namespace mechgraph::hostile;

namespace {

// The first thing in `text` a terminal would act on, described, or "" when there is none: a byte
// 0x00-0x08, 0x0B-0x1F or 0x7F; bytes that are not UTF-8 (a raw 0x9B among them); a C1 control
// U+0080-U+009F; a bidi embedding, override or isolate (U+202A-U+202E, U+2066-U+2069).
// Written apart from terminal_text, so that the escaper is not checked by itself.
std::string first_terminal_hazard(const std::string& text) {
  const auto at = [&](std::size_t i, const char* what) {
    char where[64];
    std::snprintf(where, sizeof where, "%s at byte %zu", what, i);
    return std::string(where) + ": ..." + text.substr(i >= 20 ? i - 20 : 0, 40) + "...";
  };
  if (const auto bad = mechgraph::first_invalid_utf8(text)) return at(*bad, "not UTF-8");
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    const auto next = [&](std::size_t k) { return i + k < text.size() ? static_cast<unsigned char>(text[i + k]) : 0; };
    if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7F) return at(i, "a C0 control or DEL");
    if (c == 0xC2 && next(1) >= 0x80 && next(1) <= 0x9F) return at(i, "a C1 control");
    if (c == 0xE2 && next(1) == 0x80 && next(2) >= 0xAA && next(2) <= 0xAE) return at(i, "a bidi embedding or override");
    if (c == 0xE2 && next(1) == 0x81 && next(2) >= 0xA6 && next(2) <= 0xA9) return at(i, "a bidi isolate");
  }
  return "";
}

// The hostile text as a YAML double-quoted scalar: OSC title, clear screen, CSI as U+009B, a
// right-to-left override, DEL, carriage return, backspace.
const std::string evil_yaml = R"("T\e]0;PWNED\a \e[2J \u009b31m \u202e \x7f \r\b end")";
// The same on a command line; and with the raw byte 0x9B (not UTF-8) as well.
const std::string evil_utf8 = "T\x1b]0;PWNED\x07 \x1b[2J \xc2\x9b" "31m \xe2\x80\xae \xe2\x81\xa6 \x7f \r\b end";
const std::string evil_raw = "T\x1b]0;PWNED\x07 \x1b[2J \xc2\x9b" "31m \x9b" "1m \xe2\x80\xae \x7f \r\b end";

std::string hostile_plugins() { return std::string(MECHGRAPH_TEST_PLUGIN_ROOT) + "/test_hostile_values"; }

void check_terminal_clean(const std::vector<std::string>& args, const Outcome& o) {
  std::string shown;
  for (const std::string& a : args) shown += mechgraph::quoted_text_excerpt(a) + " ";
  INFO("mechgraph " << shown << "-> exit " << o.exit_code << "\nstderr (excerpt): " << mechgraph::quoted_text_excerpt(o.err));
  CHECK(first_terminal_hazard(o.out) == "");
  CHECK(first_terminal_hazard(o.err) == "");
}

}  // namespace

TEST_CASE("hostile: no control sequence from a scene, a cases file, the command line or a plugin reaches the terminal",
          "[hostile][terminal]") {
  Scratch s("terminal");
  const std::string links = "[ { label: " + evil_yaml + ", nominal: 10 mm, upper: 0.1 mm, lower: -0.1 mm, sensitivity: 1 },"
                            " { label: b, nominal: 5 mm, upper: 0.1 mm, lower: -0.1 mm, sensitivity: -1 } ]";
  const std::string scene_text = "title: " + evil_yaml + "\n"
                                 "nodes:\n"
                                 "  t: { type: hostile.evil_text, params: { label: " + evil_yaml + " } }\n"
                                 "  gap: { type: stack.linear, params: { links: " + links + " } }\n"
                                 "report:\n  title: " + evil_yaml + "\n  columns: [ " + evil_yaml + " ]\n"
                                 "  rows:\n    - [ " + evil_yaml + ", [ gap.mean ], mm ]\n"
                                 "outputs: [ t.curve, gap.contribution_worst_case, gap.mean ]\n";
  const std::string scene = s.write("evil.yaml", scene_text).string();
  const std::string plain = s.write("plain.yaml", "title: " + evil_yaml + "\nnodes:\n  t: { type: hostile.evil_text }\n"
                                                  "outputs: [ t.curve ]\n").string();
  const std::string cases = s.write("cases.csv", "t.label\nplain\n\"" + evil_raw + "\"\nfail\n").string();
  const std::string dir = hostile_plugins();

  struct Case {
    std::vector<std::string> args;
    int exit_code;
    std::string shows;  // a piece of the hostile text that must still be shown (as text)
  };
  const std::vector<Case> cases_run = {
      {{"--plugin-dir", dir, "run", scene}, 0, "PWNED"},
      {{"--plugin-dir", dir, "-v", "run", scene}, 0, "PWNED"},
      {{"--plugin-dir", dir, "run", plain, "--set", "t.label=" + evil_utf8}, 0, "PWNED"},
      {{"--plugin-dir", dir, "run", plain, "--set", "t.label=" + evil_raw}, 2, "not UTF-8"},
      {{"--plugin-dir", dir, "run", plain, "--set", "t.label=fail"}, 3, "refused"},
      {{"--plugin-dir", dir, "run", plain, "--set", evil_raw + "=3"}, 2, "PWNED"},
      {{"--plugin-dir", dir, "run", s.dir.string() + "/" + evil_raw + ".yaml"}, 2, "PWNED"},
      {{"--plugin-dir", dir, "validate", scene}, 0, "valid"},
      {{"--plugin-dir", dir, "validate", plain, "--set", "t.mode=" + evil_raw}, 2, "PWNED"},
      {{"--plugin-dir", dir, "describe", "hostile.evil_text"}, 0, "PWNED"},
      {{"--plugin-dir", dir, "describe", evil_raw}, 2, "PWNED"},
      {{"--plugin-dir", dir, "plugins"}, 0, "PWNED"},
      {{"--plugin-dir", dir, "-v", "sweep", plain, "--cases", cases, "--out", (s.dir / "rows.csv").string()}, 0, "PWNED"},
      {{"--plugin-dir", dir, "plugin-test", "hostile.evil_text"}, -2, ""},
      {{"--plugin-dir", dir, "bench", plain}, 0, ""},
      {{"--plugin-dir", dir, evil_raw}, 2, "PWNED"},
  };
  for (const Case& c : cases_run) {
    const Outcome o = run_mechgraph(c.args, s.dir);
    INFO("stderr: " << mechgraph::quoted_text_excerpt(o.err, 400));
    check_terminal_clean(c.args, o);
    if (c.exit_code != -2) CHECK(o.exit_code == c.exit_code);
    if (!c.shows.empty()) CHECK_THAT(o.out + o.err, Contains(c.shows));
  }
}
