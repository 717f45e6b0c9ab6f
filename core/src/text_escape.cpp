#include <mechgraph/text_escape.hpp>

namespace mechgraph {
namespace {

constexpr std::string_view replacement = "\xEF\xBF\xBD";  // U+FFFD

// Length of the well-formed UTF-8 sequence at text[i], or 0 when the byte there starts none
// (Unicode 15, table 3-7: the second byte's range depends on the first).
std::size_t sequence_length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b0 = byte(i);
  if (b0 < 0x80) return 1;
  std::size_t n = 0;
  unsigned char lo = 0x80, hi = 0xBF;
  if (b0 >= 0xC2 && b0 <= 0xDF) n = 2;
  else if (b0 == 0xE0) { n = 3; lo = 0xA0; }
  else if ((b0 >= 0xE1 && b0 <= 0xEC) || b0 == 0xEE || b0 == 0xEF) n = 3;
  else if (b0 == 0xED) { n = 3; hi = 0x9F; }  // no surrogates
  else if (b0 == 0xF0) { n = 4; lo = 0x90; }
  else if (b0 >= 0xF1 && b0 <= 0xF3) n = 4;
  else if (b0 == 0xF4) { n = 4; hi = 0x8F; }  // nothing above U+10FFFF
  else return 0;
  if (i + n > text.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  return n;
}

bool is_control(unsigned char c) { return c < 0x20 || c == 0x7F; }

// Calls emit(piece) for each character of `text`, ill-formed bytes as U+FFFD.
template <class Emit>
void for_each_character(std::string_view text, Emit emit) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = sequence_length(text, i);
    if (n == 0) {
      emit(replacement);
      ++i;
    } else {
      emit(text.substr(i, n));
      i += n;
    }
  }
}

}  // namespace

std::optional<std::size_t> first_invalid_utf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = sequence_length(text, i);
    if (n == 0) return i;
    i += n;
  }
  return std::nullopt;
}

std::string utf8_sanitized(std::string_view text) {
  if (!first_invalid_utf8(text)) return std::string(text);
  std::string out;
  for_each_character(text, [&](std::string_view c) { out += c; });
  return out;
}

std::string json_string(std::string_view text) {
  static constexpr char hex[] = "0123456789abcdef";
  std::string out = "\"";
  out.reserve(text.size() + 2);
  for_each_character(text, [&](std::string_view c) {
    if (c.size() == 1) {
      const auto ch = static_cast<unsigned char>(c[0]);
      switch (ch) {
        case '"': out += "\\\""; return;
        case '\\': out += "\\\\"; return;
        case '\n': out += "\\n"; return;
        case '\t': out += "\\t"; return;
        case '\r': out += "\\r"; return;
        default:
          if (ch < 0x20) {
            out += "\\u00";
            out += hex[ch >> 4];
            out += hex[ch & 0xF];
            return;
          }
      }
    }
    out += c;
  });
  return out + "\"";
}

std::string html_text(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for_each_character(text, [&](std::string_view c) {
    if (c.size() == 1) {
      switch (c[0]) {
        case '&': out += "&amp;"; return;
        case '<': out += "&lt;"; return;
        case '>': out += "&gt;"; return;
        case '"': out += "&quot;"; return;
        case '\'': out += "&#39;"; return;
        case '\t': case '\n': out += c; return;
        default:
          if (is_control(static_cast<unsigned char>(c[0]))) return;
      }
    }
    out += c;
  });
  return out;
}

std::string file_url(std::string_view absolute_path) {
  static constexpr char hex[] = "0123456789ABCDEF";
  std::string out = "file://";
  for (const char ch : absolute_path) {
    const auto c = static_cast<unsigned char>(ch);
    const bool unreserved = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' ||
                            c == '.' || c == '_' || c == '~' || c == '/';
    if (unreserved) {
      out += ch;
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 0xF];
    }
  }
  return out;
}

std::string gnuplot_string(std::string_view text) {
  std::string out = "'";
  for_each_character(text, [&](std::string_view c) {
    if (c.size() == 1) {
      const char ch = c[0];
      if (ch == '\'') {
        // gnuplot 5.4's scanner loses a doubled quote right after the opening quote or after
        // another doubled quote ('''a', 'it''''s': the label vanishes); a zero-width space
        // (U+200B) between them keeps the text as it reads.
        if (out.back() == '\'') out += "\xE2\x80\x8B";
        out += "''";
        return;
      }
      if (ch == '`') { out += "\xCA\xBB"; return; }   // U+02BB, a turned comma: not a backquote
      if (ch == '@') { out += "\xEF\xBC\xA0"; return; }  // U+FF20, the full-width commercial at
      if (is_control(static_cast<unsigned char>(ch))) { out += ' '; return; }
    }
    out += c;
  });
  return out + "'";
}

std::string dot_string(std::string_view text) {
  std::string out = "\"";
  for_each_character(text, [&](std::string_view c) {
    if (c.size() == 1) {
      const char ch = c[0];
      if (ch == '"' || ch == '\\') { out += '\\'; out += ch; return; }
      if (ch == '\n') { out += "\\n"; return; }
      if (is_control(static_cast<unsigned char>(ch))) return;
    }
    out += c;
  });
  return out + "\"";
}

namespace {

// Whether the character `c` (one well-formed UTF-8 sequence) may reach a terminal.
bool terminal_shows(std::string_view c, TerminalLines lines) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(c[k]); };
  if (c.size() == 1) {
    if (c[0] == '\n' || c[0] == '\t') return lines == TerminalLines::kept;
    return !is_control(byte(0));
  }
  if (c.size() == 2) return !(byte(0) == 0xC2 && byte(1) < 0xA0);  // U+0080..U+009F, the C1 controls
  if (c.size() == 3 && byte(0) == 0xE2) {
    if (byte(1) == 0x80 && byte(2) >= 0xAA && byte(2) <= 0xAE) return false;  // U+202A..U+202E
    if (byte(1) == 0x81 && byte(2) >= 0xA6 && byte(2) <= 0xA9) return false;  // U+2066..U+2069
  }
  return true;
}

}  // namespace

std::string terminal_text(std::string_view text, TerminalLines lines) {
  std::string out;
  out.reserve(text.size());
  for_each_character(text, [&](std::string_view c) { out += terminal_shows(c, lines) ? c : std::string_view("?"); });
  return out;
}

bool is_terminal_safe(std::string_view text, TerminalLines lines) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = sequence_length(text, i);
    if (n == 0 || !terminal_shows(text.substr(i, n), lines)) return false;
    i += n;
  }
  return true;
}

}  // namespace mechgraph
