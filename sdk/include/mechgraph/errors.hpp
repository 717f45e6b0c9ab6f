#pragma once
// The error classes a user can tell apart, each mapped to one exit code by the host:
// 2 scene or usage, 3 evaluation, 4 plugin load, 5 writing results.
#include <mechgraph/export.hpp>

#include <stdexcept>
#include <string>

namespace mechgraph {

/// Raised inside a node's evaluate(): names the parameter (or input) at fault and the limit broken.
/// The evaluator adds the node's name.
class MECHGRAPH_INTERFACE NodeError : public std::runtime_error {
 public:
  ~NodeError() override;
  NodeError(std::string parameter, const std::string& message)
      : std::runtime_error(message), parameter_(std::move(parameter)) {}
  const std::string& parameter() const { return parameter_; }

 private:
  std::string parameter_;
};

/// Evaluation failed in a named node (exit code 3).
class MECHGRAPH_INTERFACE EvaluationError : public std::runtime_error {
 public:
  ~EvaluationError() override;
  using std::runtime_error::runtime_error;
};

/// Scene could not be loaded or validated (exit code 2). The message begins with file:line:column.
class MECHGRAPH_INTERFACE SceneError : public std::runtime_error {
 public:
  ~SceneError() override;
  using std::runtime_error::runtime_error;
};

/// A plugin could not be loaded (exit code 4).
class MECHGRAPH_INTERFACE PluginError : public std::runtime_error {
 public:
  ~PluginError() override;
  using std::runtime_error::runtime_error;
};

/// Results could not be written (exit code 5): the message names the path and the system's reason.
class MECHGRAPH_INTERFACE IoError : public std::runtime_error {
 public:
  ~IoError() override;
  using std::runtime_error::runtime_error;
};

}  // namespace mechgraph
