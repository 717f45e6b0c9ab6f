#pragma once
// A block of cam laws (mechgraph/block.hpp): one CamLaw per case of a block, or one for every
// case. A failed case holds none. What a consumer asks of case i it asks of law(i), so every
// closed-form query a law offers (monotone runs, integrals) serves the block path unchanged.
#include <mechgraph/block.hpp>
#include <mechgraph/domain/cam_law.hpp>

#include <memory>
#include <vector>

namespace mechgraph {

class MECHGRAPH_INTERFACE CamLawBlock final : public DomainBlock {
 public:
  ~CamLawBlock() override;  // out of line (key function, sdk/src/block.cpp)
  explicit CamLawBlock(std::vector<std::shared_ptr<const CamLaw>> laws) : laws_(std::move(laws)) {}
  std::string_view kind() const override { return CamLaw::kind_name; }
  std::size_t size() const override { return laws_.size(); }
  std::string contract_problem(std::size_t i) const override;
  /// Case i's law (the only one when the block holds one for every case).
  const CamLaw& law(std::size_t i) const { return *laws_[laws_.size() == 1 ? 0 : i]; }
  const std::shared_ptr<const CamLaw>& shared(std::size_t i) const { return laws_[laws_.size() == 1 ? 0 : i]; }

 private:
  std::vector<std::shared_ptr<const CamLaw>> laws_;
};

}  // namespace mechgraph
