#include <mechgraph/json_writer.hpp>
#include <mechgraph/text_escape.hpp>

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace mechgraph {

void JsonWriter::separate() {
  if (after_key_) {
    after_key_ = false;
    return;
  }
  if (!first_.empty()) {
    if (!first_.back()) out_ << ',';
    first_.back() = false;
  }
}

JsonWriter& JsonWriter::begin_object() {
  separate();
  out_ << '{';
  first_.push_back(true);
  return *this;
}
JsonWriter& JsonWriter::end_object() {
  first_.pop_back();
  out_ << '}';
  return *this;
}
JsonWriter& JsonWriter::begin_array() {
  separate();
  out_ << '[';
  first_.push_back(true);
  return *this;
}
JsonWriter& JsonWriter::end_array() {
  first_.pop_back();
  out_ << ']';
  return *this;
}
JsonWriter& JsonWriter::key(std::string_view name) {
  value(name);
  out_ << ':';
  after_key_ = true;
  return *this;
}
JsonWriter& JsonWriter::value(std::string_view text) {
  separate();
  out_ << '"';
  // Ill-formed UTF-8 (a plugin's message, bytes from a file) becomes U+FFFD: the output stays JSON.
  const std::string clean = utf8_sanitized(text);
  for (char c : clean) {
    switch (c) {
      case '"': out_ << "\\\""; break;
      case '\\': out_ << "\\\\"; break;
      case '\n': out_ << "\\n"; break;
      case '\t': out_ << "\\t"; break;
      case '\r': out_ << "\\r"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          const char* hex = "0123456789abcdef";
          out_ << "\\u00" << hex[(c >> 4) & 0xf] << hex[c & 0xf];
        } else {
          out_ << c;
        }
    }
  }
  out_ << '"';
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

}  // namespace mechgraph
