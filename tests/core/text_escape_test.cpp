// The one escaping function per output format (text_escape.hpp), against hand-worked cases and, on
// random bytes, against the property that matters: what comes out is valid in its format and holds
// nothing that format would execute or read as markup.
#include <mechgraph/bounded_read.hpp>
#include <mechgraph/json_writer.hpp>
#include <mechgraph/bounded_read.hpp>
#include <mechgraph/text_escape.hpp>

#include <catch2/catch.hpp>

#include <random>
#include <sstream>

using namespace mechgraph;

TEST_CASE("UTF-8 validation follows Unicode's table of well-formed sequences", "[escape]") {
  CHECK_FALSE(first_invalid_utf8("plain ascii"));
  CHECK_FALSE(first_invalid_utf8("caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80"));  // é € 😀
  CHECK(first_invalid_utf8("ab\xFF") == 2u);
  CHECK(first_invalid_utf8("\xC0\xAF") == 0u);          // overlong '/'
  CHECK(first_invalid_utf8("x\xED\xA0\x80") == 1u);     // a surrogate
  CHECK(first_invalid_utf8("\xF4\x90\x80\x80") == 0u);  // above U+10FFFF
  CHECK(first_invalid_utf8("\xE2\x82") == 0u);          // cut short
  CHECK(utf8_sanitized("a\xFF" "b") == "a\xEF\xBF\xBD" "b");
}

TEST_CASE("HTML text: markup characters as entities, controls dropped", "[escape]") {
  CHECK(html_text("<script>alert('x') & \"y\"</script>") == "&lt;script&gt;alert(&#39;x&#39;) &amp; &quot;y&quot;&lt;/script&gt;");
  CHECK(html_text("a\x01\x7f" "b\n") == "ab\n");
  CHECK(html_text("\xFF") == "\xEF\xBF\xBD");
}

TEST_CASE("gnuplot strings: single-quoted, quote doubled, nothing that ends or substitutes a command", "[escape]") {
  CHECK(gnuplot_string("it's") == "'it''s'");
  // gnuplot 5.4 drops a string whose doubled quote follows the opening quote or another one.
  CHECK(gnuplot_string("it''s") == "'it''\xE2\x80\x8B''s'");
  CHECK(gnuplot_string("'a") == "'\xE2\x80\x8B''a'");
  CHECK(gnuplot_string("a\nsystem(\"id\")\n#") == "'a system(\"id\") #'");
  CHECK(gnuplot_string("`id` @m") == "'\xCA\xBBid\xCA\xBB \xEF\xBC\xA0m'");
}

TEST_CASE("DOT strings: double-quoted, quote and backslash escaped, line breaks as backslash-n", "[escape]") {
  CHECK(dot_string("k\" shape=box URL=\"javascript:alert(1)") == "\"k\\\" shape=box URL=\\\"javascript:alert(1)\"");
  CHECK(dot_string("a\\N\nb") == "\"a\\\\N\\nb\"");
}

TEST_CASE("terminal text: no escape sequence, C1 control or DEL reaches the screen", "[escape]") {
  CHECK(terminal_text("a\x1b]0;owned\x07" "b\tc\n") == "a?]0;owned?b\tc\n");
  CHECK(terminal_text("\xC2\x9B" "31m \x7f \xC2\xA0 \xC3\xA9") == "?31m ? \xC2\xA0 \xC3\xA9");  // CSI as C1; NBSP and é kept
  CHECK(terminal_text("\x9B" "31m") == "\xEF\xBF\xBD" "31m");                  // the raw C1 byte is not UTF-8
  CHECK(terminal_text("\xC2\x80\xC2\x9F\xC2\x85") == "???");                  // every C1 control, NEL included
  // Bidi embeddings, overrides and isolates (U+202A..U+202E, U+2066..U+2069) would reorder the
  // text after them; the marks U+200E/U+200F and everything around the ranges stay.
  CHECK(terminal_text("a\xE2\x80\xAE" "b\xE2\x80\xAA\xE2\x81\xA6\xE2\x81\xA9" "c") == "a?b???c");
  CHECK(terminal_text("\xE2\x80\xA9\xE2\x80\xAF\xE2\x81\xA5\xE2\x81\xAA\xE2\x80\x8F") ==
        "\xE2\x80\xA9\xE2\x80\xAF\xE2\x81\xA5\xE2\x81\xAA\xE2\x80\x8F");
  // One line: a label cannot start a line of its own.
  CHECK(terminal_text("a\nb\tc\rd", TerminalLines::one) == "a?b?c?d");
  CHECK(is_terminal_safe("a\tb\n\xC3\xA9"));
  CHECK_FALSE(is_terminal_safe("a\tb", TerminalLines::one));
  CHECK_FALSE(is_terminal_safe("\xE2\x81\xA7"));
  CHECK_FALSE(is_terminal_safe("\x9B"));
  CHECK(terminal_text(terminal_text("\x1b\x9b\xC2\x9B")) == terminal_text("\x1b\x9b\xC2\x9B"));  // idempotent
}

TEST_CASE("escaping random bytes always gives valid text of the format", "[escape]") {
  std::mt19937 rng(20261125);
  std::uniform_int_distribution<int> byte(0, 255), length(0, 40);
  for (int trial = 0; trial < 20000; ++trial) {
    std::string text;
    for (int i = length(rng); i > 0; --i) text += static_cast<char>(byte(rng));
    CAPTURE(text);
    const std::string h = html_text(text);
    CHECK_FALSE(first_invalid_utf8(h));
    CHECK(h.find_first_of("<>\"'") == std::string::npos);
    const std::string g = gnuplot_string(text);
    CHECK_FALSE(first_invalid_utf8(g));
    REQUIRE(g.size() >= 2);
    const std::string inner = g.substr(1, g.size() - 2);
    CHECK(inner.find_first_of("`@\n\r") == std::string::npos);
    // Quotes inside come in pairs: the string cannot be closed early.
    for (std::size_t q = inner.find('\''); q != std::string::npos; q = inner.find('\'', q + 2)) CHECK(inner[q + 1] == '\'');
    CHECK(inner.rfind("''", 0) != 0);
    CHECK(inner.find("''''") == std::string::npos);
    const std::string d = dot_string(text);
    CHECK_FALSE(first_invalid_utf8(d));
    for (std::size_t i = 1; i + 1 < d.size(); ++i) {
      if (d[i] == '\\') { ++i; continue; }
      CHECK(d[i] != '"');
    }
    const std::string t = terminal_text(text);
    CHECK_FALSE(first_invalid_utf8(t));
    for (unsigned char c : t) CHECK((c >= 0x20 || c == '\t' || c == '\n'));
    CHECK(t.find("\xC2\x9B") == std::string::npos);
    CHECK(is_terminal_safe(t));
    CHECK(is_terminal_safe(terminal_text(text, TerminalLines::one), TerminalLines::one));
    std::ostringstream json;
    JsonWriter(json).value(text);
    CHECK_FALSE(first_invalid_utf8(json.str()));
    // An excerpt for an error message: printable ASCII only, bounded.
    const std::string e = quoted_text_excerpt(text);
    CHECK(e.size() <= 2 + 4 * 80 + 3);
    for (char c : e) CHECK((c >= 0x20 && c < 0x7f));
  }
}

TEST_CASE("file URLs: a path stays a path, whatever its folder names hold", "[escape]") {
  CHECK(file_url("/tmp/report/report.html") == "file:///tmp/report/report.html");
  CHECK(file_url("/tmp/a#b?c%d e/r.html") == "file:///tmp/a%23b%3Fc%25d%20e/r.html");
  CHECK(file_url("/tmp/\xC3\xA9t\xC3\xA9") == "file:///tmp/%C3%A9t%C3%A9");  // UTF-8 bytes, each encoded
  CHECK(file_url("/x\n\"<>") == "file:///x%0A%22%3C%3E");
}
