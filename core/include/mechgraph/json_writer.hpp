#pragma once
// A small streaming JSON writer: objects, arrays, strings (escaped), numbers with round-trip
// precision. Non-finite numbers cannot be written (they never leave a node).
#include <ostream>
#include <string_view>
#include <vector>

namespace mechgraph {

class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& out) : out_(out) {}
  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  JsonWriter& key(std::string_view name);
  JsonWriter& value(std::string_view text);
  JsonWriter& value(const char* text) { return value(std::string_view(text)); }
  JsonWriter& value(double number);
  JsonWriter& value(bool flag);
  JsonWriter& value(long number);
  JsonWriter& null();
  JsonWriter& numbers(const std::vector<double>& values);

 private:
  void separate();
  std::ostream& out_;
  std::vector<bool> first_;  // per open container: no element written yet
  bool after_key_ = false;
};

}  // namespace mechgraph
