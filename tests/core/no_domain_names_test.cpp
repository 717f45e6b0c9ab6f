// The host knows no domain (issue 30, item 2; docs/design/sdk-1.0.md, section 5): hosts/ and core/
// present what ports declare and never recognise a node type, port or channel by a domain name.
// This scans their sources (code, strings and comments alike) for the words of the built-in
// plugins' domain, case-insensitively, as whole words and as parts of identifiers split at '_' and
// at a lower-to-upper case change (cam_angle, CamLaw), and fails naming file:line and the word.
// tests/core/domain_words.allow names the few exact lines allowed, each with its reason.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// The built-in plugins' words: cams and valve trains, springs, followers, backlash chains, joints.
const std::set<std::string> domain_words = {
    "cam",    "cams",    "crank",     "lift",     "lifts",   "valve",  "valves", "spring", "springs", "nose",
    "follower", "followers", "contour", "contours", "svaj",  "tappet", "rocker", "lobe",   "lobes",   "tdc",
    "bdc",    "atdc",    "lash",      "coil",     "coils",   "backlash", "joint", "joints", "gear",  "gears"};

// The words of a line: letters and digits, split at '_' and where a lower-case letter meets an
// upper-case one.
std::vector<std::string> words_of(const std::string& line) {
  std::vector<std::string> out;
  std::string word;
  auto flush = [&] {
    if (!word.empty()) out.push_back(word);
    word.clear();
  };
  for (std::size_t i = 0; i < line.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(line[i]);
    if (!std::isalnum(c)) {
      flush();
      continue;
    }
    if (std::isupper(c) && i > 0 && std::islower(static_cast<unsigned char>(line[i - 1]))) flush();
    word += static_cast<char>(std::tolower(c));
  }
  flush();
  return out;
}

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

// "path<TAB>exact line (trimmed)"; lines starting '#' are the reasons.
std::set<std::pair<std::string, std::string>> allowed_lines(const fs::path& file) {
  std::set<std::pair<std::string, std::string>> out;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    const auto tab = line.find('\t');
    if (tab == std::string::npos) continue;
    out.emplace(line.substr(0, tab), trimmed(line.substr(tab + 1)));
  }
  return out;
}

struct Hit {
  std::string where, word, line;
};

std::vector<Hit> scan(const fs::path& root, const std::vector<std::string>& folders,
                      const std::set<std::pair<std::string, std::string>>& allowed, std::set<std::pair<std::string, std::string>>* used) {
  std::vector<Hit> hits;
  for (const std::string& folder : folders) {
    for (const auto& entry : fs::recursive_directory_iterator(root / folder)) {
      if (!entry.is_regular_file()) continue;
      const std::string ext = entry.path().extension().string(), name = entry.path().filename().string();
      if (ext != ".cpp" && ext != ".hpp" && ext != ".h" && ext != ".in" && name != "CMakeLists.txt") continue;
      const std::string rel = fs::relative(entry.path(), root).generic_string();
      std::ifstream in(entry.path());
      std::size_t n = 0;
      for (std::string line; std::getline(in, line);) {
        ++n;
        for (const std::string& w : words_of(line)) {
          if (!domain_words.count(w)) continue;
          if (allowed.count({rel, trimmed(line)})) {
            if (used) used->emplace(rel, trimmed(line));
            break;
          }
          hits.push_back({rel + ":" + std::to_string(n), w, trimmed(line)});
          break;
        }
      }
    }
  }
  return hits;
}

}  // namespace

TEST_CASE("the words of a line split at '_', case changes and punctuation", "[core][domain]") {
  CHECK(words_of("CamLaw cam_angle") == std::vector<std::string>{"cam", "law", "cam", "angle"});
  CHECK(words_of("// a camera's \"liftoff\" at TDC") == std::vector<std::string>{"a", "camera", "s", "liftoff", "at", "tdc"});
}

TEST_CASE("hosts/ and core/ name no domain: no cam, valve, spring, lift, crank ...", "[core][domain]") {
  const fs::path root = MECHGRAPH_SOURCE_DIR;
  const auto allowed = allowed_lines(root / "tests/core/domain_words.allow");
  std::set<std::pair<std::string, std::string>> used;
  const std::vector<Hit> hits = scan(root, {"hosts", "core"}, allowed, &used);
  std::ostringstream text;
  for (const Hit& h : hits) text << h.where << ": '" << h.word << "' in: " << h.line << "\n";
  INFO(text.str());
  CHECK(hits.empty());
  // Every allowed line is still there: the list never outlives its reason.
  std::ostringstream stale;
  for (const auto& a : allowed)
    if (!used.count(a)) stale << a.first << ": " << a.second << "\n";
  INFO("allowed lines no longer found:\n" << stale.str());
  CHECK(stale.str().empty());
}

TEST_CASE("the domain scan finds a domain word where one is", "[core][domain]") {
  // The scan over the plugins (which are the domain) finds plenty: the test can fail.
  const fs::path root = MECHGRAPH_SOURCE_DIR;
  CHECK(scan(root, {"plugins/cams"}, {}, nullptr).size() > 100);
}
