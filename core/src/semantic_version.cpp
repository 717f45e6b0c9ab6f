#include <mechgraph/semantic_version.hpp>

#include <charconv>
#include <stdexcept>

namespace mechgraph {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// Up to three dot-separated non-negative integers; `parts` says how many were given.
std::optional<SemanticVersion> parse_parts(std::string_view text, int& parts) {
  SemanticVersion v;
  int* fields[3] = {&v.major, &v.minor, &v.patch};
  parts = 0;
  while (true) {
    if (parts == 3 || text.empty()) return std::nullopt;
    const char* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, *fields[parts]);
    if (ec != std::errc() || ptr == text.data() || *fields[parts] < 0) return std::nullopt;
    ++parts;
    text.remove_prefix(static_cast<std::size_t>(ptr - text.data()));
    if (text.empty()) return v;
    if (text.front() != '.') return std::nullopt;
    text.remove_prefix(1);
  }
}

}  // namespace

std::optional<SemanticVersion> SemanticVersion::parse(std::string_view text) {
  int parts = 0;
  auto v = parse_parts(trim(text), parts);
  if (!v || parts != 3) return std::nullopt;
  return v;
}

std::optional<SemanticVersion> SemanticVersion::parse_partial(std::string_view text) {
  int parts = 0;
  return parse_parts(trim(text), parts);
}

std::string SemanticVersion::str() const {
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
}

VersionRequirement VersionRequirement::parse(std::string_view text) {
  VersionRequirement r;
  r.text_ = std::string(trim(text));
  std::string_view rest = text;
  while (true) {
    const std::size_t comma = rest.find(',');
    std::string_view clause = trim(rest.substr(0, comma));
    Op op = Op::eq;
    for (auto [prefix, o] : {std::pair{">=", Op::ge}, {"<=", Op::le}, {"==", Op::eq}, {">", Op::gt}, {"<", Op::lt},
                             {"=", Op::eq}, {"^", Op::caret}, {"~", Op::tilde}}) {
      if (clause.substr(0, std::string_view(prefix).size()) == prefix) {
        op = o;
        clause = trim(clause.substr(std::string_view(prefix).size()));
        break;
      }
    }
    auto v = SemanticVersion::parse_partial(clause);
    if (!v)
      throw std::invalid_argument("'" + std::string(trim(text)) +
                                  "' is not a version requirement; write comparisons such as \">=0.2\", \"^1.1\", "
                                  "\"~0.3.1\", \"==1.0.0\" or \">=0.2, <1\"");
    r.clauses_.push_back({op, *v});
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  return r;
}

bool VersionRequirement::satisfied_by(const SemanticVersion& v) const {
  for (const Clause& c : clauses_) {
    bool ok = false;
    switch (c.op) {
      case Op::ge: ok = v >= c.version; break;
      case Op::gt: ok = v > c.version; break;
      case Op::le: ok = v <= c.version; break;
      case Op::lt: ok = v < c.version; break;
      case Op::eq: ok = v == c.version; break;
      case Op::caret:
        ok = v >= c.version && v.major == c.version.major && (c.version.major != 0 || v.minor == c.version.minor);
        break;
      case Op::tilde: ok = v >= c.version && v.major == c.version.major && v.minor == c.version.minor; break;
    }
    if (!ok) return false;
  }
  return true;
}

}  // namespace mechgraph
