// The key functions of the block interfaces (sdk/include/mechgraph/block.hpp): one vtable and one
// RTTI each, in libmechgraph_sdk, so that the host's dynamic_cast finds a plugin's BlockEvaluation.
#include <mechgraph/block.hpp>
#include <mechgraph/domain/cam_law_block.hpp>
#include <mechgraph/domain/valve_motion_block.hpp>

namespace mechgraph {

DomainBlock::~DomainBlock() = default;
BlockEvaluation::~BlockEvaluation() = default;
CamLawBlock::~CamLawBlock() = default;
ValveMotionBlock::~ValveMotionBlock() = default;

BlockColumn BlockInputs::scalar(std::string_view port) const {
  auto it = scalars_.find(port);
  if (it == scalars_.end()) throw NodeError(std::string(port), "input '" + std::string(port) + "' is not connected");
  return it->second;
}

std::string CamLawBlock::contract_problem(std::size_t i) const {
  const CamLaw* law = laws_[laws_.size() == 1 ? 0 : i].get();
  return law ? law->contract_problem() : std::string();
}

}  // namespace mechgraph
