#pragma once
// Semantic versions of plugins (MAJOR.MINOR.PATCH, https://semver.org without pre-release tags) and
// the requirements a scene states on them: `requires: { myplugin: ">=1.0, <2" }`.
// A requirement is one or more comparisons joined by commas, all of which must hold:
//   >=V  >V  <=V  <V  ==V (or =V, or V alone)  ^V (same major, or same minor while major is 0, and >= V)
//   ~V (same major.minor, >= V).
// Missing parts of V count as 0 ("0.2" is 0.2.0).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph {

struct SemanticVersion {
  int major = 0;
  int minor = 0;
  int patch = 0;

  /// "1.2.3" only (all three parts, digits); nullopt otherwise.
  static std::optional<SemanticVersion> parse(std::string_view text);
  /// "1", "1.2" or "1.2.3"; missing parts are 0.
  static std::optional<SemanticVersion> parse_partial(std::string_view text);
  std::string str() const;
  auto operator<=>(const SemanticVersion&) const = default;
};

class VersionRequirement {
 public:
  /// Throws std::invalid_argument with a message saying what is wrong and what is accepted.
  static VersionRequirement parse(std::string_view text);
  bool satisfied_by(const SemanticVersion& v) const;
  const std::string& text() const { return text_; }

 private:
  enum class Op { ge, gt, le, lt, eq, caret, tilde };
  struct Clause {
    Op op;
    SemanticVersion version;
  };
  std::vector<Clause> clauses_;
  std::string text_;
};

}  // namespace mechgraph
