#pragma once
// One escaping function per output format. Every piece of text that came from a user (a scene, a
// file it names, the command line) or from a plugin passes through the function of the format it
// is written into, and through nothing else: no writer builds its own quoting. CSV has its own
// header (csv.hpp: csv_field), JSON json_string (used by json_writer.hpp for keys and values).
//
// Error messages quote user text with quoted_text_excerpt (bounded_read.hpp, in the SDK so that
// plugins use the same).
//
// The functions never fail: text that cannot be represented (control characters where the format
// has no escape for them, bytes that are not UTF-8) is replaced, not passed through.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace mechgraph {

/// The offset of the first byte that does not belong to a well-formed UTF-8 sequence (overlong
/// forms, surrogates and code points above U+10FFFF are ill-formed), or nullopt when all are.
std::optional<std::size_t> first_invalid_utf8(std::string_view text);

/// `text` with every ill-formed UTF-8 byte replaced by U+FFFD.
std::string utf8_sanitized(std::string_view text);

/// A JSON string, quotes included (RFC 8259): '"' and '\\' escaped, every C0 control (U+0000 to
/// U+001F) escaped (\\n, \\t, \\r, else \\u00XX), ill-formed UTF-8 replaced by U+FFFD. DEL, the C1
/// controls, the bidirectional controls and U+2028/U+2029 are written as \\uXXXX too: valid JSON
/// either way, but so raw JSON on a terminal moves no cursor (lossless: a parser reads them back).
/// The one escaper of every string JsonWriter writes.
std::string json_string(std::string_view text);

/// HTML text or a double-quoted attribute value: & < > " ' as entities, ill-formed UTF-8 replaced,
/// C0 controls other than tab and line feed (and DEL) dropped.
std::string html_text(std::string_view text);

/// A file:// URL for an absolute path: every byte outside RFC 3986's unreserved set and '/' is
/// percent-encoded (a folder named "a#b?c%d e" stays a path, never a fragment or a query).
std::string file_url(std::string_view absolute_path);

/// A gnuplot string constant, quotes included: single-quoted (gnuplot performs no backslash,
/// backquote or macro processing inside single quotes), a quote doubled (with a zero-width space,
/// U+200B, before a doubled quote that follows the opening quote or another doubled quote: gnuplot
/// 5.4 drops such a string), line breaks and other controls as spaces (a line break would end the command), backquotes and '@' replaced by look-
/// alikes so that no later edit to double quotes can turn them into command substitution.
std::string gnuplot_string(std::string_view text);

/// A Graphviz DOT ID, quotes included: a double-quoted string with '"' and '\' escaped, line breaks
/// as "\n" (DOT's own line break in labels), other controls dropped, ill-formed UTF-8 replaced.
std::string dot_string(std::string_view text);

/// Whether terminal_text keeps line feed and tab (text of several lines: a report, a node type's
/// description) or shows them as '?' too (one cell, label or name inside a line: a label cannot
/// then start a line of its own that looks like a result).
enum class TerminalLines { kept, one };

/// Text for a terminal, the one function every piece of text shown on a terminal passes through
/// (the command line's text output as a whole, and every log message: mechgraph/host/terminal_output.hpp).
/// Shown as '?': C0 controls other than tab and line feed (with TerminalLines::one those too), DEL,
/// C1 controls U+0080..U+009F (an escape sequence, ESC or the single-byte CSI, could rewrite the
/// screen, set the window title or hide lines), and the bidirectional embedding, override and
/// isolate controls U+202A..U+202E, U+2066..U+2069 (they reorder what follows, so text could read
/// other than it is). Bytes that are not well-formed UTF-8 (a raw 0x9B among them) become U+FFFD.
std::string terminal_text(std::string_view text, TerminalLines lines = TerminalLines::kept);

/// Whether `text` is safe to show as terminal_text makes it: well-formed UTF-8 holding none of the
/// characters above. The tests and the fuzz target check output with it.
bool is_terminal_safe(std::string_view text, TerminalLines lines = TerminalLines::kept);

}  // namespace mechgraph
