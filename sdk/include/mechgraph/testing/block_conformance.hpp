#pragma once
// The block check of the node conformance suite (mechgraph/block.hpp): a node type that offers
// BlockEvaluation gives, for every case of a block it does not fail, the very numbers its single
// evaluation gives. Run by check_node_type (node_conformance.hpp) after the single evaluation.
#include <mechgraph/block.hpp>
#include <mechgraph/domain/cam_law_block.hpp>
#include <mechgraph/domain/valve_motion_block.hpp>
#include <mechgraph/node.hpp>
#include <mechgraph/testing/cam_law_conformance.hpp>
#include <mechgraph/testing/node_harness.hpp>
#include <mechgraph/testing/report.hpp>

#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace mechgraph::testing {

inline constexpr const char* block_check = "blocks: every case of a block gives the single evaluation's numbers";

namespace detail {

// A block of one case holding a single input value, for the interfaces the SDK has blocks of;
// nullptr for any other.
inline std::shared_ptr<const DomainBlock> block_of_one(const std::shared_ptr<const DomainObject>& object) {
  if (auto law = std::dynamic_pointer_cast<const CamLaw>(object))
    return std::make_shared<const CamLawBlock>(std::vector<std::shared_ptr<const CamLaw>>{law});
  if (auto motion = std::dynamic_pointer_cast<const ValveMotion>(object)) {
    // The motion's cam, kept alive by the motion that holds it.
    auto cams = std::make_shared<const CamLawBlock>(
        std::vector<std::shared_ptr<const CamLaw>>{std::shared_ptr<const CamLaw>(motion, &motion->cam())});
    auto block = std::make_shared<ValveMotionBlock>(cams, 1);
    block->open_begin[0] = motion->open_begin();
    block->open_end[0] = motion->open_end();
    block->rocker_ratio[0] = motion->rocker_ratio();
    block->lash[0] = motion->lash();
    block->camshaft_speed[0] = motion->camshaft_speed();
    return block;
  }
  return nullptr;
}

}  // namespace detail

/// Appends the block check to `r` (skipped, with the reason, when the type offers no blocks for
/// these parameters and outputs or an input has no block form).
inline void check_block_evaluation(const NodeType& type, const ParamSet& params, const InputSet& inputs, const OutputSet& single,
                                   Report& r, const std::string& suite) {
  const auto* blocks = dynamic_cast<const BlockEvaluation*>(&type);
  if (!blocks) return;
  const NodeInfo& info = type.info();
  constexpr std::size_t n = 3;
  std::vector<std::string> wanted, varied;
  for (const auto& [name, value] : params.all())
    if (value.kind == ParamKind::number) varied.push_back(name);
  ParamSet fixed = params;
  std::vector<std::vector<double>> columns;
  std::map<std::string, BlockColumn, std::less<>> varied_columns;
  columns.reserve(varied.size());
  for (const std::string& name : varied) {
    columns.emplace_back(n, params.number(name));
    varied_columns[name] = BlockColumn{columns.back().data(), 1};
  }
  try {
    // The outputs it offers blocks for (each asked alone, then all together), every number varied.
    for (const auto& [port, value] : single.all()) {
      if (value.kind() != ValueKind::scalar && value.kind() != ValueKind::handle) continue;
      const std::vector<std::string> one{port};
      if (blocks->block_supported(BlockRequest{params, one, varied})) wanted.push_back(port);
    }
    if (wanted.empty() || !blocks->block_supported(BlockRequest{params, wanted, varied})) {
      r.skip(suite, block_check, "it offers blocks, but not for its outputs with every number parameter varied");
      return;
    }
    BlockInputs block_inputs;
    std::vector<double> scalar_inputs;
    scalar_inputs.reserve(info.inputs.size());  // never reallocated: the columns point into it
    for (const PortSpec& in : info.inputs) {
      if (inputs.count(in.name) == 0) continue;
      const Value& v = inputs.value(in.name);
      if (v.kind() == ValueKind::scalar) {
        scalar_inputs.push_back(v.as_scalar());
        block_inputs.add_scalar(in.name, BlockColumn{&scalar_inputs.back(), 0});
      } else if (auto block = v.kind() == ValueKind::handle ? detail::block_of_one(v.as_handle()) : nullptr) {
        block_inputs.add_handle(in.name, block);
      } else {
        r.skip(suite, block_check, "input '" + in.name + "' has no block form the kit knows");
        return;
      }
    }
    BlockParams block_params(fixed, varied_columns);
    BlockOutputs outputs(n);
    for (const std::string& port : wanted)
      if (single.all().at(port).kind() == ValueKind::scalar) outputs.want_scalar(port);
    BlockCases cases(n);
    HarnessContext context;
    blocks->evaluate_block(block_params, block_inputs, outputs, cases, context);
    std::string bad;
    std::size_t live = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (cases.failed(i)) continue;
      ++live;
      for (const auto& [port, column] : outputs.scalars()) {
        const double expected = single.all().at(port).as_scalar();
        if (!(column[i] == expected) && bad.empty())
          bad = "case " + std::to_string(i) + ", output '" + port + "': " + detail::num(column[i]) + " where the single evaluation gave " +
                detail::num(expected);
      }
    }
    for (const std::string& port : wanted) {
      if (single.all().at(port).kind() != ValueKind::handle || !bad.empty()) continue;
      const auto it = outputs.handles().find(port);
      const PortSpec* spec = info.find_output(port);
      if (it == outputs.handles().end() || !it->second) bad = "no block at output '" + port + "'";
      else if (it->second->kind() != spec->handle_kind) bad = "the block at '" + port + "' is not a " + spec->handle_kind;
      else if (it->second->size() != n && it->second->size() != 1) bad = "the block at '" + port + "' holds " + std::to_string(it->second->size()) + " objects for 3 cases";
      else
        for (std::size_t i = 0; i < n && bad.empty(); ++i)
          if (!cases.failed(i))
            if (const std::string problem = it->second->contract_problem(i); !problem.empty()) bad = "case " + std::to_string(i) + " at '" + port + "': " + problem;
    }
    r.add(suite, block_check, bad.empty() && live > 0,
          !bad.empty() ? bad : live == 0 ? "it failed every case the single evaluation made" : std::to_string(live) + " cases of 3, " + std::to_string(wanted.size()) + " outputs");
  } catch (const std::exception& e) {
    r.add(suite, block_check, false, std::string("the block evaluation threw: ") + e.what());
  }
}

}  // namespace mechgraph::testing
