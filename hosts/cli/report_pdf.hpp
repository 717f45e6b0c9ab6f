#pragma once
// `mechgraph report --pdf`: the report page printed to PDF by Debian's headless chromium. The page is
// opened from its file (file://, nothing else: the page loads nothing from outside, and chromium
// is started with its network features off), chromium runs from an argument vector with a time
// limit, in a throw-away folder of its own (mkdtemp) that is its profile, its HOME, its XDG folders
// and its crash-dump folder, so nothing it writes lands in the user's home; the folder is removed
// afterwards. The PDF must come back whole (pdf_problem), else the report is not published.
#include <filesystem>
#include <string>

namespace mechgraph::cli {

/// Throws IoError (naming the package to install) when no chromium is on PATH: `report --pdf`
/// asks before it runs the scene.
void require_pdf_printer();

/// Prints `dir`/report.html to `dir`/report.pdf. Throws IoError (exit 5) when chromium is not
/// installed (with the package to install), fails, runs past its time limit or writes no whole
/// PDF; the PDF is removed then.
void print_report_pdf(const std::filesystem::path& dir);

/// "" when `pdf` is a whole PDF file, else why not. Whole: it starts with "%PDF-"; it ends with
/// "%%EOF" (whitespace after it allowed), which a cut file (a full disk) has lost; the offset after
/// its last "startxref" lies inside the file and points at a cross-reference table or stream; it
/// declares a page tree with /Count > 0. When poppler's pdfinfo is on PATH, it must also read the
/// file and count more than 0 pages. Reads at most 1 GiB.
std::string pdf_problem(const std::filesystem::path& pdf);

}  // namespace mechgraph::cli
