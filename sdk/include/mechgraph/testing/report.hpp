#pragma once
// The result of a conformance suite: one line per check, passed, failed or skipped, each with what
// was measured. Header-only, so a plugin's own tests can use the kit without the host:
//
//   const auto report = mechgraph::testing::check_node_type(MyCamNode{});
//   INFO(report.str());          // Catch2 (or any framework: report.failed() is a count)
//   CHECK(report.passed());
#include <string>
#include <utility>
#include <vector>

namespace mechgraph::testing {

struct Check {
  enum class Status { passed, failed, skipped };
  std::string suite;   // "node cam.example_parabolic", "cam_law law"
  std::string name;    // "zero outside the event"
  Status status = Status::passed;
  std::string detail;  // what was measured, or why it failed or was skipped
};

class Report {
 public:
  void add(std::string suite, std::string name, bool ok, std::string detail = {}) {
    checks_.push_back({std::move(suite), std::move(name), ok ? Check::Status::passed : Check::Status::failed, std::move(detail)});
  }
  void skip(std::string suite, std::string name, std::string why) {
    checks_.push_back({std::move(suite), std::move(name), Check::Status::skipped, std::move(why)});
  }
  void append(const Report& other) { checks_.insert(checks_.end(), other.checks_.begin(), other.checks_.end()); }

  const std::vector<Check>& checks() const { return checks_; }
  int count(Check::Status s) const {
    int n = 0;
    for (const Check& c : checks_) n += c.status == s;
    return n;
  }
  int failed() const { return count(Check::Status::failed); }
  /// No check failed (skipped ones do not fail a report).
  bool passed() const { return failed() == 0; }

  /// One line per check: "PASS  suite: name (detail)".
  std::string str() const {
    std::string out;
    for (const Check& c : checks_) {
      out += c.status == Check::Status::passed ? "PASS  " : c.status == Check::Status::failed ? "FAIL  " : "SKIP  ";
      out += c.suite + ": " + c.name;
      if (!c.detail.empty()) out += " (" + c.detail + ")";
      out += "\n";
    }
    return out;
  }

 private:
  std::vector<Check> checks_;
};

}  // namespace mechgraph::testing
