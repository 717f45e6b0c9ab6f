#include "report_pdf.hpp"

#include "spawn.hpp"

#include <mechgraph/bounded_read.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/text_escape.hpp>

#include <chrono>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include <unistd.h>

namespace mechgraph::cli {
namespace {

std::string log_excerpt(const std::filesystem::path& log) {
  std::ifstream in(log);
  std::string text(2048, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  return utf8_sanitized(text);
}

std::filesystem::path pdf_printer() {
  std::optional<std::filesystem::path> chromium = find_program("chromium");
  if (!chromium) chromium = find_program("chromium-browser");
  if (!chromium)
    throw IoError("mechgraph report --pdf prints the page with chromium, which is not installed (apt-get install chromium); "
                  "without --pdf the HTML report needs only gnuplot");
  return *chromium;
}

}  // namespace

void require_pdf_printer() { (void)pdf_printer(); }

void print_report_pdf(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  const fs::path chromium = pdf_printer();
  const fs::path page = fs::absolute(dir / "report.html");
  const fs::path pdf = fs::absolute(dir / "report.pdf");
  // A profile of its own, outside the report folder, removed afterwards.
  const fs::path profile = fs::temp_directory_path() / ("mechgraph-chromium-" + std::to_string(::getpid()));
  fs::remove_all(profile);
  fs::create_directories(profile);
  const fs::path log = profile / "chromium.log";
  std::vector<std::string> args{"--headless",
                                "--disable-gpu",
                                "--disable-extensions",
                                "--disable-background-networking",
                                "--disable-sync",
                                "--disable-default-apps",
                                "--no-first-run",
                                "--no-pdf-header-footer",
                                "--user-data-dir=" + profile.string(),
                                "--print-to-pdf=" + pdf.string(),
                                file_url(page.string())};
  // Chromium's sandbox cannot start as root (a container's usual user); the page is our own file.
  if (::geteuid() == 0) args.insert(args.begin() + 1, "--no-sandbox");
  const SpawnOutcome run = run_program(chromium, args, dir, log, std::chrono::minutes(2));
  const std::string why = run.succeeded() ? std::string() : log_excerpt(log);
  std::error_code ignored;
  fs::remove_all(profile, ignored);
  if (!run.succeeded()) throw IoError("chromium could not print the report to PDF (" + run.describe() + "): " + why);
  std::ifstream in(pdf, std::ios::binary);
  char magic[5] = {};
  in.read(magic, 4);
  if (!in || std::string(magic, 4) != "%PDF") throw IoError("chromium wrote no PDF of the report ('" + pdf.string() + "')");
}

}  // namespace mechgraph::cli
