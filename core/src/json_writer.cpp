#include <mechgraph/json_writer.hpp>
#include <mechgraph/text_escape.hpp>

#include <charconv>
#include <cmath>
#include <map>
#include <stdexcept>
#include <unordered_set>

namespace mechgraph {

void JsonWriter::separate() {
  if (after_key_) {
    after_key_ = false;
    return;
  }
  if (!open_.empty()) {
    if (open_.back().object) throw std::logic_error("JSON: a value in an object needs a key first");
    if (!open_.back().empty) out_ << ',';
    open_.back().empty = false;
  }
}

JsonWriter& JsonWriter::begin_object() {
  separate();
  out_ << '{';
  open_.push_back({true, true, {}});
  return *this;
}
JsonWriter& JsonWriter::end_object() {
  if (open_.empty() || !open_.back().object || after_key_) throw std::logic_error("JSON: end_object without an open object");
  open_.pop_back();
  out_ << '}';
  return *this;
}
JsonWriter& JsonWriter::begin_array() {
  separate();
  out_ << '[';
  open_.push_back({false, true, {}});
  return *this;
}
JsonWriter& JsonWriter::end_array() {
  if (open_.empty() || open_.back().object) throw std::logic_error("JSON: end_array without an open array");
  open_.pop_back();
  out_ << ']';
  return *this;
}
JsonWriter& JsonWriter::key(std::string_view name) {
  if (open_.empty() || !open_.back().object || after_key_) throw std::logic_error("JSON: a key outside an object");
  Open& object = open_.back();
  // Compared as written (after U+FFFD replacement): two byte strings that sanitise alike are one key.
  std::string written = json_string(name);
  if (!object.keys.insert(written).second)
    throw std::logic_error("JSON: the key " + written + " would appear twice in one object");
  if (!object.empty) out_ << ',';
  object.empty = false;
  out_ << written << ':';
  after_key_ = true;
  return *this;
}
JsonWriter& JsonWriter::value(std::string_view text) {
  separate();
  out_ << json_string(text);
  return *this;
}
JsonWriter& JsonWriter::value(double number) {
  if (!std::isfinite(number)) throw std::invalid_argument("JSON cannot hold a NaN or infinite number");
  separate();
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, number);  // shortest round-trip form
  out_.write(buffer, end - buffer);
  return *this;
}
JsonWriter& JsonWriter::value(bool flag) {
  separate();
  out_ << (flag ? "true" : "false");
  return *this;
}
JsonWriter& JsonWriter::value(long number) {
  separate();
  out_ << number;
  return *this;
}
JsonWriter& JsonWriter::null() {
  separate();
  out_ << "null";
  return *this;
}
JsonWriter& JsonWriter::numbers(const std::vector<double>& values) {
  begin_array();
  for (double v : values) value(v);
  return end_array();
}

std::vector<std::string> distinct_keys(const std::vector<std::string>& given) {
  // Compared as they will be written: two names that differ only in ill-formed bytes are one key.
  std::vector<std::string> names;
  names.reserve(given.size());
  for (const std::string& n : given) names.push_back(utf8_sanitized(n));
  std::map<std::string, std::size_t> count;
  for (const std::string& n : names) ++count[n];
  std::unordered_set<std::string> taken;
  for (const std::string& n : names)
    if (count[n] == 1) taken.insert(n);
  std::map<std::string, std::size_t> next;  // per repeated name: the number its next key gets
  std::vector<std::string> keys;
  keys.reserve(names.size());
  for (const std::string& n : names) {
    if (count[n] == 1) {
      keys.push_back(n);
      continue;
    }
    std::string key;
    do key = n + " #" + std::to_string(++next[n]);
    while (!taken.insert(key).second);
    keys.push_back(std::move(key));
  }
  return keys;
}

}  // namespace mechgraph
