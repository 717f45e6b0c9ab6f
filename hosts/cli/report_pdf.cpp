#include "report_pdf.hpp"

#include "output_file.hpp"
#include "spawn.hpp"

#include <mechgraph/bounded_read.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/text_escape.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <string>
#include <system_error>
#include <vector>

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

// A fresh folder under the system's temporary folder (mkdtemp: 0700, a name no one can plant).
std::filesystem::path private_folder() {
  std::string pattern = (std::filesystem::temp_directory_path() / "mechgraph-chromium-XXXXXX").string();
  if (!::mkdtemp(pattern.data())) io_failure("make a private folder for chromium in", std::filesystem::temp_directory_path(), errno);
  return pattern;
}

// What pdfinfo (poppler-utils) says of the file, when it is installed: "" when it reads it and
// counts pages, else why not.
std::string pdfinfo_problem(const std::filesystem::path& pdf) {
  const std::optional<std::filesystem::path> pdfinfo = find_program("pdfinfo");
  if (!pdfinfo) return {};
  const std::filesystem::path log = private_folder();
  const SpawnOutcome run = run_program(*pdfinfo, {pdf.string()}, log, log / "pdfinfo.log", std::chrono::seconds(60));
  const std::string said = log_excerpt(log / "pdfinfo.log");
  std::error_code ignored;
  std::filesystem::remove_all(log, ignored);
  if (!run.succeeded()) return "pdfinfo cannot read it (" + run.describe() + ")";
  std::smatch pages;
  if (!std::regex_search(said, pages, std::regex("Pages:\\s+([0-9]+)")) || pages[1] == "0") return "pdfinfo finds no page in it";
  return {};
}

// fsync: the PDF is on the disk before the report folder is put in place.
void sync_file(const std::filesystem::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) io_failure("open", file, errno);
  FileHandle handle(fd);
  if (::fsync(fd) != 0) io_failure("write", file, errno);
}

// The largest /Count of a dictionary that is a /Type /Pages node (the page tree's root counts all
// pages), or 0. A plain scan, no regular expression over a file of megabytes.
unsigned long long page_count(const std::string& text) {
  unsigned long long most = 0;
  for (std::size_t at = text.find("/Pages"); at != std::string::npos; at = text.find("/Pages", at + 6)) {
    std::size_t before = at;
    while (before > 0 && (text[before - 1] == ' ' || text[before - 1] == '\n' || text[before - 1] == '\r')) --before;
    if (before < 5 || text.compare(before - 5, 5, "/Type") != 0) continue;
    const std::size_t open = text.rfind("<<", before), close = text.find(">>", at);
    if (open == std::string::npos || close == std::string::npos) continue;
    const std::size_t count = text.find("/Count", open);
    if (count == std::string::npos || count > close) continue;
    most = std::max(most, std::strtoull(text.c_str() + count + 6, nullptr, 10));
  }
  return most;
}

}  // namespace

void require_pdf_printer() { (void)pdf_printer(); }

std::string pdf_problem(const std::filesystem::path& pdf) {
  std::string text;
  try {
    text = read_bounded_file(pdf, std::size_t{1} << 30);
  } catch (const FileReadError& e) {
    return e.what();
  }
  if (text.rfind("%PDF-", 0) != 0) return "it does not start with %PDF-";
  std::size_t end = text.size();
  while (end > 0 && (text[end - 1] == '\n' || text[end - 1] == '\r' || text[end - 1] == ' ' || text[end - 1] == '\t')) --end;
  if (end < 5 || text.compare(end - 5, 5, "%%EOF") != 0) return "it does not end with %%EOF (cut short: a full disk?)";
  const std::size_t startxref = text.rfind("startxref");
  if (startxref == std::string::npos) return "it has no startxref";
  const std::size_t digits = text.find_first_of("0123456789", startxref + 9);
  const unsigned long long offset = digits == std::string::npos ? ~0ULL : std::strtoull(text.c_str() + digits, nullptr, 10);
  if (offset >= startxref) return "its startxref points outside the file";
  const std::string at = text.substr(offset, 32);
  if (at.rfind("xref", 0) != 0 && !std::regex_search(at, std::regex("^[0-9]+\\s+[0-9]+\\s+obj")))
    return "its startxref does not point at a cross-reference";
  if (page_count(text) == 0) return "it has no page tree with pages";
  return pdfinfo_problem(pdf);
}

void print_report_pdf(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  const fs::path chromium = pdf_printer();
  const fs::path page = fs::absolute(dir / "report.html");
  const fs::path pdf = fs::absolute(dir / "report.pdf");
  // A folder of its own, outside the report folder and the user's home, removed afterwards.
  const fs::path own = private_folder();
  const fs::path profile = own / "profile", home = own / "home", crashes = own / "crashes";
  std::error_code ec;
  for (const fs::path& p : {profile, home, crashes, home / ".config", home / ".cache", home / ".local/share", own / "tmp"})
    fs::create_directories(p, ec);
  if (ec) {
    fs::remove_all(own, ec);
    io_failure("make a private folder for chromium in", own, ec.value());
  }
  const fs::path log = own / "chromium.log";
  std::vector<std::string> args{"--headless",
                                "--disable-gpu",
                                "--disable-extensions",
                                "--disable-background-networking",
                                "--disable-sync",
                                "--disable-default-apps",
                                "--disable-breakpad",
                                "--disable-crash-reporter",
                                "--no-first-run",
                                "--no-pdf-header-footer",
                                "--crash-dumps-dir=" + crashes.string(),
                                "--user-data-dir=" + profile.string(),
                                "--print-to-pdf=" + pdf.string(),
                                file_url(page.string())};
  // Chromium's sandbox cannot start as root (a container's usual user); the page is our own file.
  if (::geteuid() == 0) args.insert(args.begin() + 1, "--no-sandbox");
  const std::vector<std::pair<std::string, std::string>> environment{
      {"HOME", home.string()},
      {"XDG_CONFIG_HOME", (home / ".config").string()},
      {"XDG_CACHE_HOME", (home / ".cache").string()},
      {"XDG_DATA_HOME", (home / ".local/share").string()},
      {"TMPDIR", (own / "tmp").string()},
      {"BREAKPAD_DUMP_LOCATION", crashes.string()}};
  const SpawnOutcome run = run_program(chromium, args, dir, log, std::chrono::minutes(2), environment);
  const std::string why = run.succeeded() ? std::string() : log_excerpt(log);
  fs::remove_all(own, ec);
  auto refuse = [&](const std::string& message) {
    std::error_code ignored;
    fs::remove(pdf, ignored);  // no part of a PDF is left behind
    throw IoError(message);
  };
  if (!run.succeeded()) refuse("chromium could not print the report to PDF (" + run.describe() + "): " + why);
  if (const std::string problem = pdf_problem(pdf); !problem.empty())
    refuse("chromium wrote no whole PDF of the report ('" + pdf.string() + "': " + problem + ")");
  sync_file(pdf);
}

}  // namespace mechgraph::cli
