// csv_field / append_csv_field: the one CSV escaping function, against its definition (csv_text,
// then RFC 4180 quoting) and on the cells that decide it (line breaks, formula starts, numbers).
#include <mechgraph/csv.hpp>

#include <catch2/catch.hpp>

#include <random>

using namespace mechgraph;

namespace {

// The definition, written out the slow way: the text a reader gets back, quoted when it holds a
// comma or a quote (quotes doubled).
std::string reference_field(std::string_view text) {
  const std::string plain = csv_text(text);
  if (plain.find_first_of(",\"") == std::string::npos) return plain;
  std::string out = "\"";
  for (char c : plain) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace

TEST_CASE("csv_field: the cells that decide quoting and formula neutralising") {
  CHECK(csv_field("1.5") == "1.5");
  CHECK(csv_field("-1.5e-3") == "-1.5e-3");  // a number, not a formula
  CHECK(csv_field("-") == "-");              // the empty-cell mark
  CHECK(csv_field("-x") == "'-x");
  CHECK(csv_field("=SUM(A1)") == "'=SUM(A1)");
  CHECK(csv_field("@x,y") == "\"'@x,y\"");
  CHECK(csv_field("a\"b") == "\"a\"\"b\"");
  CHECK(csv_field("a\nb") == "a b");
  CHECK(csv_field("\r=1") == " =1");  // the CR is a space before the formula rule is applied
  CHECK(csv_field("\n-2") == " -2");
  CHECK(csv_field("\t1") == "'\t1");
  CHECK(csv_field("") == "");
  std::string row = "x";
  append_csv_field(row, "=1");
  CHECK(row == "x'=1");  // appends, leaves what was there
}

TEST_CASE("csv_field equals its definition on random cells of the deciding characters") {
  std::mt19937_64 random(7);
  const std::string alphabet = "-+=@\t\r\n,\"0123456789.eEa ";
  std::uniform_int_distribution<std::size_t> pick(0, alphabet.size() - 1), length(0, 6);
  for (int k = 0; k < 20000; ++k) {
    std::string text;
    for (std::size_t n = length(random); n > 0; --n) text += alphabet[pick(random)];
    INFO("cell '" << text << "'");
    REQUIRE(csv_field(text) == reference_field(text));
    REQUIRE(split_csv_line(csv_field(text)) == std::vector<std::string>{csv_text(text)});
  }
}

TEST_CASE("split_plain_csv_line gives split_csv_line's fields as views, and declines quotes") {
  // Second method: split_csv_line, over random lines of the characters that decide a split.
  std::mt19937_64 random(11);
  const std::string alphabet = ",,a1 .\t\r-";
  std::uniform_int_distribution<std::size_t> pick(0, alphabet.size() - 1), length(0, 9);
  std::vector<std::string_view> views;
  for (int k = 0; k < 20000; ++k) {
    std::string line;
    for (std::size_t n = length(random); n > 0; --n) line += alphabet[pick(random)];
    INFO("line '" << line << "'");
    REQUIRE(split_plain_csv_line(line, views));
    const std::vector<std::string> expected = split_csv_line(line);
    REQUIRE(std::vector<std::string>(views.begin(), views.end()) == expected);
  }
  CHECK_FALSE(split_plain_csv_line("a,\"b,c\"", views));
  CHECK(views.empty());
  REQUIRE(split_plain_csv_line("", views));
  CHECK(views == std::vector<std::string_view>{""});
}
