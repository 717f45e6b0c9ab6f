#pragma once
// What reaches a terminal. Text a command prints (tables, labels, notes, names and descriptions from
// scenes and plugins) and every log message pass through terminal_text (text_escape.hpp) here, as a
// whole, so no piece of scene or plugin text can bring an escape sequence along, whichever code
// path formatted it. Machine formats (JSON, CSV rows, DOT) are written by their own writers and
// escaped by their own functions; they do not come through here.
#include <spdlog/sinks/sink.h>

#include <string_view>

namespace mechgraph::host {

/// Writes a command's text output (the text mode of run, validate, plugins, describe, ...) to
/// standard output through terminal_text.
void print_text(std::string_view text);

/// A log sink that passes every message through terminal_text before `inner` formats it (level,
/// colours and pattern stay the inner sink's): a message quoting a label, a file name or a plugin's
/// words cannot write control sequences to stderr.
spdlog::sink_ptr terminal_safe_sink(spdlog::sink_ptr inner);

/// The default logger for a host: named `name`, writing to stderr (coloured when stderr is a
/// terminal) through terminal_safe_sink.
void use_terminal_safe_logger(const char* name);

}  // namespace mechgraph::host
