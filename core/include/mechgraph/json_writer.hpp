#pragma once
// A small streaming JSON writer: objects, arrays, strings (escaped), numbers with round-trip
// precision. Non-finite numbers cannot be written (they never leave a node).
//
// What it writes is always RFC 8259 JSON that a strict parser accepts:
//  - every string, keys included, goes through json_string (text_escape.hpp): quotes, backslashes
//    and every control character escaped, ill-formed UTF-8 replaced by U+FFFD;
//  - an object never holds the same key twice: key() throws std::logic_error for a repeated key
//    (a reader of duplicate keys keeps one of them, silently). Keys made from user text that may
//    repeat (link labels) go through distinct_keys first.
#include <ostream>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

namespace mechgraph {

class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& out) : out_(out) {}
  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  /// Throws std::logic_error when the open object holds `name` already, or no object is open.
  JsonWriter& key(std::string_view name);
  JsonWriter& value(std::string_view text);
  JsonWriter& value(const char* text) { return value(std::string_view(text)); }
  JsonWriter& value(double number);
  JsonWriter& value(bool flag);
  JsonWriter& value(long number);
  JsonWriter& null();
  JsonWriter& numbers(const std::vector<double>& values);

 private:
  struct Open {
    bool object = false;
    bool empty = true;                     // no element written yet
    std::unordered_set<std::string> keys;  // an object's keys so far
  };
  void separate();
  std::ostream& out_;
  std::vector<Open> open_;
  bool after_key_ = false;
};

/// Object keys for `names` that may repeat (e.g. the labels of a tolerance chain's links): a name
/// given once is its own key; each of n > 1 equal names is numbered in order, "sleeve #1" ...
/// "sleeve #n", so no reader mistakes one of them for all of them; a numbered key that is already
/// taken (a link really named "sleeve #2") is numbered on until it is free. Names are compared as
/// JSON writes them (ill-formed UTF-8 replaced by U+FFFD). The result has the size and order of
/// `names` and no two keys JsonWriter would write alike.
std::vector<std::string> distinct_keys(const std::vector<std::string>& names);

}  // namespace mechgraph
