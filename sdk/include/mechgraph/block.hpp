#pragma once
// Block evaluation: a node type that can evaluate many cases of a sweep at once (structure of
// arrays) offers BlockEvaluation beside NodeType (docs/writing-plugins.md, "Blocks of cases").
//
// A block is n cases of one graph that differ only in some number parameters. The host gives a
// node each varied parameter as a column (one value per case) and every other parameter as the
// node's ParamSet; scalar ports travel as columns, domain objects as a DomainBlock (one object per
// case, or one for all). The node fills a column per wanted scalar output. No per-case maps, no
// per-case checks of the graph, no per-case output sets: that bookkeeping is what a block saves.
//
// Contract
//  - evaluate_block() gives, for every case it does not fail, the very numbers evaluate() gives
//    for that case (the same formulas in the same order; a test holds the built-in types to it).
//  - A case the node cannot do (a NodeError, a value it would refuse, a quantity it cannot give on
//    the block path) is marked with BlockCases::fail(i): the host redoes that case alone through
//    evaluate(), which gives its result or its error message exactly as a run would.
//  - block_supported() says, before any case runs, whether this node instance (its fixed
//    parameters, the outputs read of it, the parameters that vary) can go on the block path; the
//    host uses blocks only when every node a sweep needs says yes, else every case runs alone.
//  - Like evaluate(), evaluate_block() is const, keeps no state and may run on many threads at
//    once (each on its own block).
#include <mechgraph/export.hpp>
#include <mechgraph/node.hpp>
#include <mechgraph/params.hpp>

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mechgraph {

/// One number per case of a block (stride 1), or one number for every case (stride 0).
struct BlockColumn {
  const double* data = nullptr;
  std::size_t stride = 0;
  double operator[](std::size_t i) const { return data[i * stride]; }
};

/// A block of domain objects of one kind: one per case, or (size() == 1) one for every case.
class MECHGRAPH_INTERFACE DomainBlock {
 public:
  virtual ~DomainBlock();  // out of line (key function, sdk/src/block.cpp)
  virtual std::string_view kind() const = 0;
  virtual std::size_t size() const = 0;
  /// The interface's contract for case i's object (DomainObject::contract_problem); the host
  /// checks every object of every block a node outputs, as it checks a single handle.
  virtual std::string contract_problem(std::size_t /*i*/) const { return {}; }
};

/// Which cases of a block are still alive. A case failed by one node is skipped by the nodes
/// after it and redone alone by the host.
class BlockCases {
 public:
  explicit BlockCases(std::size_t n) : failed_(n, 0) {}
  std::size_t size() const { return failed_.size(); }
  bool failed(std::size_t i) const { return failed_[i] != 0; }
  void fail(std::size_t i) { failed_[i] = 1; }

 private:
  std::vector<std::uint8_t> failed_;
};

/// The parameters of a block: the node's ParamSet, and a column for each varied number.
class BlockParams {
 public:
  /// `fixed` holds every parameter (a varied one holds some case's value: read it by column).
  BlockParams(ParamSet& fixed, std::map<std::string, BlockColumn, std::less<>> varied)
      : fixed_(fixed), varied_(std::move(varied)) {
    for (const auto& [name, column] : varied_) slots_.emplace_back(&fixed_.slot(name), column);
  }
  /// The fixed parameters; a varied one there holds whichever case was written last.
  const ParamSet& fixed() const { return fixed_; }
  bool varies(std::string_view name) const { return varied_.find(name) != varied_.end(); }
  /// Parameter `name` as a column: the varied values, or the fixed value for every case.
  BlockColumn number(std::string_view name) const {
    if (auto it = varied_.find(name); it != varied_.end()) return it->second;
    return {&fixed_.get(name).number, 0};
  }
  /// The parameters of case i as one evaluation sees them: the varied values of case i written
  /// into the set (in place), which is returned. Valid until the next call.
  const ParamSet& of_case(std::size_t i) const {
    for (const auto& [slot, column] : slots_) slot->number = column[i];
    return fixed_;
  }

 private:
  ParamSet& fixed_;
  std::map<std::string, BlockColumn, std::less<>> varied_;
  std::vector<std::pair<ParamValue*, BlockColumn>> slots_;
};

/// The inputs of a block: a column per scalar port, a DomainBlock per handle port.
class BlockInputs {
 public:
  void add_scalar(std::string port, BlockColumn column) { scalars_[std::move(port)] = column; }
  void add_handle(std::string port, std::shared_ptr<const DomainBlock> block) { handles_[std::move(port)] = std::move(block); }
  BlockColumn scalar(std::string_view port) const;
  /// The block behind a handle port, as its interface; throws NodeError if it is not one.
  template <class T>
  const T& handle(std::string_view port) const {
    auto it = handles_.find(port);
    const T* block = it != handles_.end() ? dynamic_cast<const T*>(it->second.get()) : nullptr;
    if (!block) throw NodeError(std::string(port), "input '" + std::string(port) + "' does not carry the expected block of domain objects");
    return *block;
  }
  /// The same block, shared (to keep it in a block this node outputs).
  template <class T>
  std::shared_ptr<const T> shared_handle(std::string_view port) const {
    handle<T>(port);  // refuses a missing or foreign block
    return std::static_pointer_cast<const T>(handles_.find(port)->second);
  }

 private:
  std::map<std::string, BlockColumn, std::less<>> scalars_;
  std::map<std::string, std::shared_ptr<const DomainBlock>, std::less<>> handles_;
};

/// The outputs of a block: the host gives a column (n values) for each scalar output read
/// downstream; a handle output is set as a DomainBlock.
class BlockOutputs {
 public:
  explicit BlockOutputs(std::size_t n) : n_(n) {}
  std::size_t size() const { return n_; }
  /// The column to fill for scalar output `port`, or nullptr when nothing reads it.
  double* scalar(std::string_view port) {
    auto it = scalars_.find(port);
    return it != scalars_.end() ? it->second.data() : nullptr;
  }
  void set_handle(std::string port, std::shared_ptr<const DomainBlock> block) { handles_[std::move(port)] = std::move(block); }

  // The host's side.
  void want_scalar(std::string port) { scalars_[std::move(port)].assign(n_, 0.0); }
  const std::map<std::string, std::vector<double>, std::less<>>& scalars() const { return scalars_; }
  const std::map<std::string, std::shared_ptr<const DomainBlock>, std::less<>>& handles() const { return handles_; }

 private:
  std::size_t n_;
  std::map<std::string, std::vector<double>, std::less<>> scalars_;
  std::map<std::string, std::shared_ptr<const DomainBlock>, std::less<>> handles_;
};

/// What the host asks before it plans blocks: this node's outputs read downstream (sorted) and
/// its parameters that vary from case to case.
struct BlockRequest {
  const ParamSet& params;
  const std::vector<std::string>& wanted;
  const std::vector<std::string>& varied;
  bool wants(std::string_view output) const {
    for (const std::string& w : wanted)
      if (w == output) return true;
    return false;
  }
};

/// The optional capability of a NodeType (inherit both): evaluating a block of cases at once.
class MECHGRAPH_INTERFACE BlockEvaluation {
 public:
  virtual ~BlockEvaluation();  // out of line (key function, sdk/src/block.cpp)
  /// Whether evaluate_block() can make every output in `request.wanted` for these parameters.
  virtual bool block_supported(const BlockRequest& request) const = 0;
  /// Evaluates the live cases of `cases`; see the contract above. Work counters go to `context`
  /// summed over the block.
  virtual void evaluate_block(const BlockParams& params, const BlockInputs& inputs, BlockOutputs& outputs,
                              BlockCases& cases, EvalContext& context) const = 0;
};

/// Runs `body(i)` for every live case of `cases`; a NodeError from a case fails that case (the
/// host redoes it alone and reports the error as a run would).
template <class Body>
void for_each_live_case(BlockCases& cases, Body&& body) {
  for (std::size_t i = 0; i < cases.size(); ++i) {
    if (cases.failed(i)) continue;
    try {
      body(i);
    } catch (const NodeError&) {
      cases.fail(i);
    }
  }
}

}  // namespace mechgraph
