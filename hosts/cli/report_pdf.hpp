#pragma once
// `mechgraph report --pdf`: the report page printed to PDF by Debian's headless chromium. The page is
// opened from its file (file://, nothing else: the page loads nothing from outside, and chromium
// is started with its network features off), chromium runs from an argument vector with a time
// limit and a throw-away profile folder, and the PDF must come back starting with "%PDF".
#include <filesystem>

namespace mechgraph::cli {

/// Throws IoError (naming the package to install) when no chromium is on PATH: `report --pdf`
/// asks before it runs the scene.
void require_pdf_printer();

/// Prints `dir`/report.html to `dir`/report.pdf. Throws IoError when chromium is not installed (with
/// the package to install), fails, runs past its time limit or writes no PDF.
void print_report_pdf(const std::filesystem::path& dir);

}  // namespace mechgraph::cli
