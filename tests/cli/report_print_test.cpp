// A report as it is printed and as its CSVs are read: every table of `report --pdf` fits the A4
// page (nothing beyond the right margin, no column dropped: a table too wide is printed in parts
// that repeat its key column), checked on the PDF itself with poppler's pdftotext; and the CSV
// beside each of the page's tables holds the numbers the table shows, in its units.
#include "file_support.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <map>
#include <sstream>

#include <unistd.h>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {

namespace fs = std::filesystem;

fs::path fresh_folder(const std::string& name) { return absent_dir("mg_print", name); }

std::string scene(const char* name) { return (std::filesystem::path(MECHGRAPH_SOURCE_DIR) / "scenes" / name).string(); }

// Ten lobes side by side: a report table of ten columns, events tables of twelve columns (the
// installed lobes), lengths in inches (the scene's units) and angles in degrees (the reader's).
const char* const wide_scene = R"(title: Ten lobes side by side
units: { length: in }
params:
  base: 17 mm
nodes:
  a: { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 120 deg, base_radius: $base, accel_angle: 18 deg, nose_timing: 108 deg } }
  b: { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 124 deg, base_radius: $base, accel_angle: 18 deg, nose_timing: -110 deg } }
  c: { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 128 deg, base_radius: $base, accel_angle: 18 deg } }
  d: { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 132 deg, base_radius: $base, accel_angle: 18 deg } }
  e: { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 136 deg, base_radius: $base, accel_angle: 18 deg } }
  f: { type: cam.kurz, params: { max_lift: 9 mm, action_angle: 120 deg, base_radius: $base, accel_angle: 18 deg } }
  g: { type: cam.kurz, params: { max_lift: 9 mm, action_angle: 124 deg, base_radius: $base, accel_angle: 18 deg } }
  h: { type: cam.kurz, params: { max_lift: 9 mm, action_angle: 128 deg, base_radius: $base, accel_angle: 18 deg } }
  i: { type: cam.kurz, params: { max_lift: 9 mm, action_angle: 132 deg, base_radius: $base, accel_angle: 18 deg } }
  j: { type: cam.kurz, params: { max_lift: 9 mm, action_angle: 136 deg, base_radius: $base, accel_angle: 18 deg } }
report:
  title: Ten lobes
  columns:
    "lobe A 120 deg": { cam: a }
    "lobe B 124 deg": { cam: b }
    "lobe C 128 deg": { cam: c }
    "lobe D 132 deg": { cam: d }
    "lobe E 136 deg": { cam: e }
    "lobe F 120 deg": { cam: f }
    "lobe G 124 deg": { cam: g }
    "lobe H 128 deg": { cam: h }
    "lobe I 132 deg": { cam: i }
    "lobe J 136 deg": { cam: j }
  rows:
    - [ largest lift, cam.max_lift, "" ]
    - [ largest velocity over cam angle, cam.max_velocity, "" ]
)";

fs::path wide_scene_file() {
  const fs::path file = fs::temp_directory_path() / ("mg_print_" + std::to_string(::getpid())) / "ten_lobes.yaml";
  fs::create_directories(file.parent_path());
  std::ofstream(file) << wide_scene;
  return file;
}

std::string unescaped(std::string text) {
  static const std::pair<const char*, const char*> entities[] = {
      {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&#39;", "'"}, {"&#x27;", "'"}, {"&amp;", "&"}};
  for (const auto& [entity, plain] : entities)
    for (std::size_t at = text.find(entity); at != std::string::npos; at = text.find(entity, at + 1))
      text.replace(at, std::string(entity).size(), plain);
  return text;
}

// A cell's text: tags out, a line break a space, entities decoded.
std::string cell_text(const std::string& html) {
  std::string text;
  bool in_tag = false;
  for (char c : html) {
    if (c == '<') in_tag = true, text += ' ';  // <br> between a name and its unit
    else if (c == '>') in_tag = false;
    else if (!in_tag) text += c;
  }
  return unescaped(text);
}

std::vector<std::string> words_of(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

// A table of the page as the screen shows it (the whole table): its header cells and its rows.
struct PageTable {
  std::string title;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

// The text between `open` and `close` from `at` on ("" when absent); `at` moves past it. A plain
// scan: std::regex recurses per character and the page is megabytes.
std::string between(const std::string& text, const std::string& open, const std::string& close, std::size_t& at) {
  const std::size_t start = text.find(open, at);
  if (start == std::string::npos) return at = std::string::npos, std::string();
  const std::size_t end = text.find(close, start + open.size());
  if (end == std::string::npos) return at = std::string::npos, std::string();
  at = end + close.size();
  return text.substr(start + open.size(), end - start - open.size());
}

// The value of attribute `name` in a tag's text (`xMax="12.5"`).
double attribute(const std::string& tag, const std::string& name) {
  const std::size_t at = tag.find(name + "=\"");
  REQUIRE(at != std::string::npos);
  return std::stod(tag.substr(at + name.size() + 2));
}

std::vector<PageTable> screen_tables(const std::string& page) {
  // Each table under its heading: <h2>TITLE</h2>\n<div class="scroll..."><table ...>...</table>.
  std::vector<PageTable> tables;
  for (std::size_t at = 0; at != std::string::npos;) {
    PageTable parsed;
    parsed.title = unescaped(between(page, "<h2>", "</h2>\n", at));
    if (at == std::string::npos) break;
    if (page.compare(at, 18, "<div class=\"scroll") != 0) continue;
    const std::string body = between(page, "<table", "</table>", at);
    for (std::size_t r = 0; r != std::string::npos;) {
      const std::string row = between(body, "<tr>", "</tr>", r);
      if (r == std::string::npos) break;
      std::vector<std::string> cells;
      for (std::size_t c = 0; c < row.size();) {
        const std::size_t open = row.find("<t", c);
        if (open == std::string::npos) break;
        const std::size_t start = row.find('>', open) + 1, end = row.find("</t", start);
        cells.push_back(cell_text(row.substr(start, end - start)));
        c = end + 5;
      }
      if (parsed.header.empty()) parsed.header = cells;
      else parsed.rows.push_back(cells);
    }
    tables.push_back(std::move(parsed));
  }
  return tables;
}

std::vector<std::string> csv_fields(const std::string& line) {
  // The CSVs compared here hold names, units and numbers: no quoted commas.
  std::vector<std::string> fields;
  std::istringstream in(line);
  for (std::string f; std::getline(in, f, ',');) fields.push_back(f);
  return fields;
}

// "opening after TDC [deg (crank)]" -> "deg": the unit a CSV header gives.
std::string page_unit(const std::string& header) {
  const std::size_t open = header.rfind('['), close = header.rfind(']');
  if (open == std::string::npos || close == std::string::npos) return {};
  const std::string unit = header.substr(open + 1, close - open - 1);
  return unit.substr(0, unit.find(" ("));
}

// Every small table of the page (an events table) against the CSV beside it: the same columns,
// the header's unit the page's, every number the page shows.
void check_csvs_against_page(const fs::path& dir) {
  const std::vector<PageTable> tables = screen_tables(slurp(dir / "report.html"));
  std::size_t compared = 0;
  for (const PageTable& t : tables) {
    const fs::path csv = dir / (t.title + ".csv");
    if (!fs::exists(csv)) continue;  // a report table (table_N.csv, its units a column of its own)
    INFO(csv.string());
    std::istringstream in(slurp(csv));
    std::string line;
    REQUIRE(std::getline(in, line));
    const std::vector<std::string> header = csv_fields(line);
    REQUIRE(header.size() == t.header.size());
    for (std::size_t k = 0; k < header.size(); ++k) {
      INFO(header[k] << " under the page's " << t.header[k]);
      CHECK(page_unit(header[k]) == page_unit(t.header[k]));
    }
    for (const std::vector<std::string>& page_row : t.rows) {
      REQUIRE(std::getline(in, line));
      const std::vector<std::string> values = csv_fields(line);
      REQUIRE(values.size() == page_row.size());
      for (std::size_t k = 0; k < values.size(); ++k) {
        INFO(header[k] << ": CSV " << values[k] << ", page " << page_row[k]);
        // The page shows 6 significant digits.
        CHECK(std::stod(values[k]) == Approx(std::stod(page_row[k])).epsilon(1e-5).margin(1e-9));
      }
    }
    CHECK(!std::getline(in, line));  // no row the page leaves out
    ++compared;
  }
  CHECK(compared >= 3);
}

struct PdfWord {
  double x_min, x_max;
  std::string text;
};

struct PdfPage {
  double width = 0.0;
  std::vector<PdfWord> words;
};

// The PDF's words with their boxes, by pdftotext -bbox-layout (poppler-utils).
std::vector<PdfPage> pdf_words(const fs::path& pdf) {
  const fs::path boxes = pdf.parent_path() / "report.words.html";
  const auto r = run_command("pdftotext -bbox-layout '" + pdf.string() + "' '" + boxes.string() + "'");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::string text = slurp(boxes);
  std::vector<PdfPage> pages;
  for (std::size_t at = 0;;) {
    const std::size_t start = text.find("<page ", at);
    if (start == std::string::npos) break;
    const std::size_t end = text.find("</page>", start);
    REQUIRE(end != std::string::npos);
    PdfPage parsed;
    parsed.width = attribute(text.substr(start, text.find('>', start) - start), "width");
    for (std::size_t w = text.find("<word ", start); w < end; w = text.find("<word ", w + 1)) {
      const std::size_t tag_end = text.find('>', w), word_end = text.find("</word>", tag_end);
      const std::string tag = text.substr(w, tag_end - w);
      parsed.words.push_back({attribute(tag, "xMin"), attribute(tag, "xMax"), unescaped(text.substr(tag_end + 1, word_end - tag_end - 1))});
    }
    pages.push_back(std::move(parsed));
    at = end;
  }
  return pages;
}

// The printed page holds every table whole: no word beyond the margins (12 mm, the page's @page
// rule), and every word of every table's header and cells as often as the page's tables hold it
// (a column cut off at the page's edge, or left out of a printed part, is missing).
void check_pdf_fits(const fs::path& dir) {
  const std::vector<PdfPage> pages = pdf_words(dir / "report.pdf");
  REQUIRE(!pages.empty());
  const double margin = 12.0 / 25.4 * 72.0, slack = 1.5;  // pt
  std::map<std::string, int> printed;
  for (std::size_t p = 0; p < pages.size(); ++p)
    for (const PdfWord& w : pages[p].words) {
      ++printed[w.text];
      INFO("page " << p + 1 << ": '" << w.text << "' from x = " << w.x_min << " to " << w.x_max << " pt of " << pages[p].width);
      CHECK(w.x_max <= pages[p].width - margin + slack);
      CHECK(w.x_min >= margin - slack);
    }
  std::map<std::string, int> shown;
  std::size_t wide = 0;
  for (const PageTable& t : screen_tables(slurp(dir / "report.html"))) {
    wide += t.header.size() > 10 ? 1 : 0;
    for (const std::string& h : t.header)
      for (const std::string& w : words_of(h)) ++shown[w];
    for (const auto& row : t.rows)
      for (const std::string& c : row)
        for (const std::string& w : words_of(c)) ++shown[w];
  }
  CHECK(wide >= 2);  // the scenes have tables wider than the page
  for (const auto& [word, count] : shown) {
    INFO("'" << word << "' is in the page's tables " << count << " times, in the PDF " << printed[word] << " times");
    CHECK(printed[word] >= count);
  }
}

bool have(const char* program) { return !find_on_path(program).empty(); }

}  // namespace

TEST_CASE("report: the CSV beside each table is in the units the table shows", "[cli][report][units]") {
  // valvetrain_cams.yaml names no units: the page shows degrees and millimetres, SI would be rad
  // and m. The ten lobes name inches for lengths and leave angles to the reader's degrees.
  for (const fs::path& file : {fs::path(scene("valvetrain_cams.yaml")), wide_scene_file()}) {
    INFO(file.string());
    const fs::path dir = fresh_folder(file.stem().string() + "_csv");
    const auto r = run_cli("-q report '" + file.string() + "' --out '" + dir.string() + "'");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    check_csvs_against_page(dir);
    if (file.stem() == "ten_lobes") CHECK_THAT(slurp(dir / "a.events.csv"), Contains("checking_lift [in],opening [deg (cam)]"));
    fs::remove_all(dir);
  }
}

TEST_CASE("report --pdf: every table fits the printed A4 page, none cut off", "[cli][report][pdf]") {
  // scripts/install-deps.sh installs both: without them the test fails rather than passing unchecked.
  if (!have("chromium") || !have("pdftotext"))
    FAIL("chromium or pdftotext (poppler-utils) is not installed (scripts/install-deps.sh installs them): the printed page cannot be checked");
  for (const fs::path& file : {fs::path(scene("valvetrain_cams.yaml")), wide_scene_file()}) {
    INFO(file.string());
    const fs::path dir = fresh_folder(file.stem().string() + "_pdf");
    const auto r = run_cli("-q report '" + file.string() + "' --out '" + dir.string() + "' --pdf");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    check_pdf_fits(dir);
    // The screen still shows each table whole; the parts are for print only.
    CHECK_THAT(slurp(dir / "report.html"), Contains("<div class=\"print\">"));
    fs::remove_all(dir);
  }
}
