#include "yaml_bounds.hpp"

#include <mechgraph/error_subject.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/scene.hpp>
#include <mechgraph/bounded_read.hpp>
#include <mechgraph/text_escape.hpp>

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

#include <cstdio>
#include <map>
#include <sstream>
#include <unordered_map>
#include <vector>

namespace mechgraph::detail {
namespace {

class BoundsWalk {
 public:
  BoundsWalk(std::string file, const YamlLimits& limits) : file_(std::move(file)), limits_(limits) {}

  void visit(const YAML::Node& n) {
    if (++visited_ > limits_.max_nodes)
      fail(n, "the scene expands to more than " + std::to_string(limits_.max_nodes) +
                  " YAML nodes (an alias counts each time it is used): too large to be a scene");
    if (!n.IsMap() && !n.IsSequence()) return;
    for (const YAML::Node& above : path_)
      if (above.is(n)) fail(n, "an alias refers to a node that contains it (a cycle): a scene is a tree");
    if (path_.size() >= limits_.max_depth)
      fail(n, "the scene nests maps and lists more than " + std::to_string(limits_.max_depth) + " levels deep");
    path_.push_back(n);
    if (n.IsMap()) {
      std::map<std::string, YAML::Mark> seen;
      for (const auto& kv : n) {
        if (kv.first.IsScalar()) {
          const auto [it, fresh] = seen.emplace(kv.first.Scalar(), kv.first.Mark());
          if (!fresh)
            fail(kv.first, "the key " + quoted_text_excerpt(kv.first.Scalar()) + " is given twice in one map (first at line " +
                               std::to_string(it->second.line + 1) + ", column " + std::to_string(it->second.column + 1) +
                               "): say it once");
        }
        visit(kv.first);
        visit(kv.second);
      }
    } else {
      for (const auto& item : n) visit(item);
    }
    path_.pop_back();
  }

 private:
  [[noreturn]] void fail(const YAML::Node& n, const std::string& message) const {
    const YAML::Mark m = n.Mark();
    const SourceLocation where = m.is_null() ? SourceLocation{file_, 0, 0} : SourceLocation{file_, m.line + 1, m.column + 1};
    throw_scene_error_at(where, message);
  }

  std::string file_;
  YamlLimits limits_;
  std::size_t visited_ = 0;
  std::vector<YAML::Node> path_;
};

// Counts what the document would build, expanding each alias by the size of the node it names.
class CountingHandler final : public YAML::EventHandler {
 public:
  CountingHandler(std::string file, const YamlLimits& limits) : file_(std::move(file)), limits_(limits) {}

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& m, YAML::anchor_t anchor) override { leaf(m, anchor); }
  void OnScalar(const YAML::Mark& m, const std::string&, YAML::anchor_t anchor, const std::string&) override { leaf(m, anchor); }
  void OnAlias(const YAML::Mark& m, YAML::anchor_t anchor) override {
    for (const Open& o : open_)
      if (o.anchor == anchor && anchor != 0) fail(m, "an alias refers to a node that contains it (a cycle): a scene is a tree");
    const auto it = size_.find(anchor);
    add(m, it == size_.end() ? 1 : it->second, 0);
  }
  void OnSequenceStart(const YAML::Mark& m, const std::string&, YAML::anchor_t anchor, YAML::EmitterStyle::value) override {
    start(m, anchor);
  }
  void OnSequenceEnd() override { end(); }
  void OnMapStart(const YAML::Mark& m, const std::string&, YAML::anchor_t anchor, YAML::EmitterStyle::value) override {
    start(m, anchor);
  }
  void OnMapEnd() override { end(); }

 private:
  struct Open {
    YAML::anchor_t anchor;
    std::size_t expanded_before;
  };

  void leaf(const YAML::Mark& m, YAML::anchor_t anchor) {
    add(m, 1, 1);
    if (anchor) size_[anchor] = 1;
  }
  void start(const YAML::Mark& m, YAML::anchor_t anchor) {
    if (open_.size() >= limits_.max_depth)
      fail(m, "the scene nests maps and lists more than " + std::to_string(limits_.max_depth) + " levels deep");
    open_.push_back({anchor, expanded_});
    add(m, 1, 1);
  }
  void end() {
    if (open_.empty()) return;
    const Open o = open_.back();
    open_.pop_back();
    if (o.anchor) size_[o.anchor] = expanded_ - o.expanded_before;
  }
  void add(const YAML::Mark& m, std::size_t expanded, std::size_t written) {
    expanded_ += expanded;
    written_ += written;
    if (written_ > limits_.max_written)
      fail(m, "the scene holds more than " + std::to_string(limits_.max_written) + " YAML nodes: too large to be a scene");
    if (expanded_ > limits_.max_nodes)
      fail(m, "the scene expands to more than " + std::to_string(limits_.max_nodes) +
                  " YAML nodes (an alias counts each time it is used): too large to be a scene");
  }
  [[noreturn]] void fail(const YAML::Mark& m, const std::string& message) const {
    throw_scene_error_at(SourceLocation{file_, m.line + 1, m.column + 1}, message);
  }

  std::string file_;
  YamlLimits limits_;
  std::vector<Open> open_;
  std::unordered_map<YAML::anchor_t, std::size_t> size_;
  std::size_t expanded_ = 0, written_ = 0;
};

}  // namespace

void check_yaml_events(std::string_view text, const std::string& file, const YamlLimits& limits) {
  std::istringstream in{std::string(text)};
  CountingHandler counter(file, limits);
  try {
    YAML::Parser parser(in);
    parser.HandleNextDocument(counter);
  } catch (const YAML::Exception&) {
    // A syntax error: YAML::Load reports it with its location next.
  }
}

void check_yaml_bounds(const YAML::Node& root, const std::string& file, const YamlLimits& limits) {
  BoundsWalk(file, limits).visit(root);
}

void check_utf8(std::string_view text, const std::string& file) {
  const std::optional<std::size_t> bad = first_invalid_utf8(text);
  if (!bad) return;
  int line = 1, column = 1;
  for (std::size_t i = 0; i < *bad; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  char hex[8];
  std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned>(static_cast<unsigned char>(text[*bad])));
  throw_scene_error_at(SourceLocation{file, line, column}, std::string("byte ") + hex +
                   " is not UTF-8: save the scene as UTF-8 text");
}

}  // namespace mechgraph::detail
