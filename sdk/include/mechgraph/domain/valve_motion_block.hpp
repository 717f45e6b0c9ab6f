#pragma once
// A block of valve motions (mechgraph/block.hpp), as structure of arrays: per case the open
// period, the rocker ratio, the lash and the camshaft speed, over a block of cam laws. Case i is
// the ValveMotion of its cam law at those numbers (mechgraph/domain/valve_motion.hpp).
#include <mechgraph/domain/cam_law_block.hpp>
#include <mechgraph/domain/valve_motion.hpp>

#include <memory>
#include <vector>

namespace mechgraph {

class MECHGRAPH_INTERFACE ValveMotionBlock final : public DomainBlock {
 public:
  ~ValveMotionBlock() override;  // out of line (key function, sdk/src/block.cpp)
  ValveMotionBlock(std::shared_ptr<const CamLawBlock> cams, std::size_t n) : cams_(std::move(cams)) {
    for (auto* column : {&open_begin, &open_end, &rocker_ratio, &lash, &camshaft_speed}) column->assign(n, 0.0);
  }
  std::string_view kind() const override { return ValveMotion::kind_name; }
  std::size_t size() const override { return open_begin.size(); }
  const CamLaw& cam(std::size_t i) const { return cams_->law(i); }
  const std::shared_ptr<const CamLaw>& shared_cam(std::size_t i) const { return cams_->shared(i); }
  /// Where case i's numbers stand in the columns (0 when the block holds one motion for every case).
  std::size_t row(std::size_t i) const { return open_begin.size() == 1 ? 0 : i; }

  std::vector<double> open_begin, open_end;  // rad: the cam angles where the valve opens and closes
  std::vector<double> rocker_ratio, lash;    // 1, m
  std::vector<double> camshaft_speed;        // rad/s

 private:
  std::shared_ptr<const CamLawBlock> cams_;
};

}  // namespace mechgraph
