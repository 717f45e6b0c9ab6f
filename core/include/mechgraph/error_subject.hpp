#pragma once
// Errors that carry what they are about as data beside their message: where in the scene
// (file:line:column), which node, which parameter. A program (the Python module) reads these fields
// instead of parsing messages. They derive from the SDK's error classes, so every catch of those
// still catches them, with the same message.
#include <mechgraph/errors.hpp>
#include <mechgraph/scene.hpp>

#include <string>

namespace mechgraph {

/// What an error is about. `where.line` is 0 when it is not a place in a file (a --set value, a
/// value from Python); `node` and `parameter` are "" when the error names none.
struct ErrorSubject {
  SourceLocation where;
  std::string node;
  std::string parameter;
};

/// A SceneError (exit code 2) with its subject: thrown where a scene's text is refused.
class MECHGRAPH_EXPORT SceneErrorAt : public SceneError {
 public:
  SceneErrorAt(ErrorSubject subject, const std::string& message) : SceneError(message), subject_(std::move(subject)) {}
  ~SceneErrorAt() override;
  const ErrorSubject& subject() const { return subject_; }

 private:
  ErrorSubject subject_;
};

/// An EvaluationError (exit code 3) of a named node, with the parameter it names (if any) and
/// where that parameter (else the node) stands in the scene.
class MECHGRAPH_EXPORT NodeEvaluationError : public EvaluationError {
 public:
  NodeEvaluationError(ErrorSubject subject, const std::string& message)
      : EvaluationError(message), subject_(std::move(subject)) {}
  ~NodeEvaluationError() override;
  const ErrorSubject& subject() const { return subject_; }

 private:
  ErrorSubject subject_;
};

/// Throws SceneErrorAt for `where`, the message starting with it ("file:line:column: message").
[[noreturn]] inline void throw_scene_error_at(const SourceLocation& where, const std::string& message) {
  throw SceneErrorAt({where, {}, {}}, where.str() + message);
}

}  // namespace mechgraph
