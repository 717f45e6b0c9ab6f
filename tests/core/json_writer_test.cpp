// The JSON writer's promises (issue 28): no key twice in one object, every string through the one
// escaper, repeated user names numbered by distinct_keys.
#include <mechgraph/json_writer.hpp>
#include <mechgraph/text_escape.hpp>

#include <catch2/catch.hpp>

#include <set>
#include <sstream>

using namespace mechgraph;

TEST_CASE("JsonWriter refuses a key twice in one object, not in two", "[json]") {
  std::ostringstream os;
  JsonWriter json(os);
  json.begin_object().key("a").value(1.0).key("b").begin_object().key("a").value(2.0).end_object();
  CHECK_THROWS_AS(json.key("a"), std::logic_error);
  // Keys that differ only in ill-formed bytes are written alike: the same key.
  std::ostringstream other;
  JsonWriter second(other);
  second.begin_object().key("x\xff").value(1.0);
  CHECK_THROWS_AS(second.key("x\xfe"), std::logic_error);
  CHECK_THROWS_AS(JsonWriter(other).key("outside"), std::logic_error);
}

TEST_CASE("distinct_keys numbers repeated names and never gives two alike", "[json]") {
  CHECK(distinct_keys({"shaft", "bearing", "sleeve", "bearing"}) == std::vector<std::string>{"shaft", "bearing #1", "sleeve", "bearing #2"});
  // A name that is already what a number would make: numbered on.
  const auto keys = distinct_keys({"bearing #1", "bearing", "bearing", "x\xff", "x\xfe"});
  CHECK(keys[0] == "bearing #1");
  CHECK(keys[1] == "bearing #2");
  CHECK(keys[2] == "bearing #3");
  CHECK(std::set<std::string>(keys.begin(), keys.end()).size() == keys.size());
  std::ostringstream os;
  JsonWriter json(os);
  json.begin_object();
  for (const std::string& k : keys) CHECK_NOTHROW(json.key(k).value(1.0));
}

TEST_CASE("json_string escapes every C0 control and keeps the rest", "[json]") {
  for (int c = 0; c < 0x20; ++c) {
    const std::string s = json_string(std::string(1, static_cast<char>(c)));
    INFO(c);
    CHECK(s.size() >= 4);
    CHECK(s[1] == '\\');
  }
  CHECK(json_string("a\"b\\c") == "\"a\\\"b\\\\c\"");
  CHECK(json_string("\x1b[31m") == "\"\\u001b[31m\"");
  CHECK(json_string("\xC2\x9B") == "\"\xC2\x9B\"");  // C1 CSI: valid JSON, kept
  CHECK(json_string("\xff") == "\"\xEF\xBF\xBD\"");
}
