// The writers' escaping (text_escape.hpp, the JSON writer) on arbitrary bytes: the result must be
// well-formed UTF-8 and hold nothing its format would read as markup, the end of a string or a
// command. A violation aborts (a find).
#include <mechgraph/json_writer.hpp>
#include <mechgraph/bounded_read.hpp>
#include <mechgraph/text_escape.hpp>

#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <vector>
#include <string>

namespace {

void require(bool ok) {
  if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  using namespace mechgraph;

  const std::string h = html_text(text);
  require(!first_invalid_utf8(h));
  require(h.find_first_of("<>\"'") == std::string::npos);

  const std::string g = gnuplot_string(text);
  require(!first_invalid_utf8(g) && g.size() >= 2 && g.front() == '\'' && g.back() == '\'');
  const std::string inner = g.substr(1, g.size() - 2);
  require(inner.find_first_of("`@\n\r") == std::string::npos);
  for (std::size_t q = inner.find('\''); q != std::string::npos; q = inner.find('\'', q + 2))
    require(q + 1 < inner.size() && inner[q + 1] == '\'');
  // What gnuplot 5.4 misreads: a doubled quote first, or two doubled quotes in a row.
  require(inner.rfind("''", 0) != 0 && inner.find("''''") == std::string::npos);

  const std::string d = dot_string(text);
  require(!first_invalid_utf8(d) && d.size() >= 2 && d.front() == '"' && d.back() == '"');
  for (std::size_t i = 1; i + 1 < d.size(); ++i) {
    if (d[i] == '\\') {
      ++i;
      require(i + 1 < d.size());  // an escape never swallows the closing quote
      continue;
    }
    require(d[i] != '"' && d[i] != '\n');
  }

  std::ostringstream json;
  JsonWriter(json).value(text);
  const std::string j = json.str();
  require(!first_invalid_utf8(j) && j.front() == '"' && j.back() == '"');
  for (std::size_t i = 1; i + 1 < j.size(); ++i) {
    if (j[i] == '\\') {
      ++i;
      continue;
    }
    require(j[i] != '"' && static_cast<unsigned char>(j[i]) >= 0x20);
  }

  // Terminal text: well-formed UTF-8 without C0 (but tab and line feed), DEL, C1 (U+0080..U+009F)
  // or bidi controls, checked byte by byte here (not with the escaper's own is_terminal_safe);
  // unchanged when it was safe already, and unchanged by a second pass.
  for (const TerminalLines lines : {TerminalLines::kept, TerminalLines::one}) {
    const std::string t = terminal_text(text, lines);
    require(!first_invalid_utf8(t));
    for (std::size_t i = 0; i < t.size(); ++i) {
      const auto c = static_cast<unsigned char>(t[i]);
      const auto next = [&](std::size_t k) { return i + k < t.size() ? static_cast<unsigned char>(t[i + k]) : 0; };
      const bool line = c == '\n' || c == '\t';
      require(!(c < 0x20 || c == 0x7F) || (line && lines == TerminalLines::kept));
      require(!(c == 0xC2 && next(1) < 0xA0));
      require(!(c == 0xE2 && next(1) == 0x80 && next(2) >= 0xAA && next(2) <= 0xAE));
      require(!(c == 0xE2 && next(1) == 0x81 && next(2) >= 0xA6 && next(2) <= 0xA9));
    }
    require(is_terminal_safe(t, lines));
    require(terminal_text(t, lines) == t);
    if (is_terminal_safe(text, lines)) require(t == text);
  }

  // Keys from user text that may repeat (link labels), split at NUL: distinct_keys makes them
  // unique, and an object of them is written without the writer refusing a key twice.
  std::vector<std::string> names;
  for (std::size_t from = 0;;) {
    const std::size_t at = text.find('\0', from);
    names.push_back(text.substr(from, at == std::string::npos ? std::string::npos : at - from));
    if (at == std::string::npos || names.size() > 64) break;
    from = at + 1;
  }
  const std::vector<std::string> keys = distinct_keys(names);
  require(keys.size() == names.size());
  std::ostringstream object;
  JsonWriter writer(object);
  writer.begin_object();
  try {
    for (const std::string& k : keys) writer.key(k).value(1.0);
  } catch (const std::logic_error&) {
    require(false);  // distinct_keys gave two keys JSON writes alike
  }
  writer.end_object();

  const std::string e = quoted_text_excerpt(text);
  require(e.size() <= 2 + 4 * 80 + 3);
  for (char c : e) require(c >= 0x20 && c < 0x7f);
  return 0;
}
