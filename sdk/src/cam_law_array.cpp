// Cam laws over arrays of cases (mechgraph/domain/cam_law_array.hpp): the key functions, the lane's
// answers that are not inline, and lanes_of.
#include <mechgraph/domain/cam_law_array.hpp>

#include <stdexcept>
#include <string>

namespace mechgraph {

CamLawArray::~CamLawArray() = default;

CamLawLane::CamLawLane(std::shared_ptr<const CamLawArray> array, std::size_t lane)
    : array_(std::move(array)), lane_(lane) {
  if (!array_) throw std::invalid_argument("CamLawLane: no array");
  if (lane_ >= array_->lanes())
    throw std::out_of_range("CamLawLane: lane " + std::to_string(lane_) + " of an array of " +
                            std::to_string(array_->lanes()));
  columns_ = array_->columns();
  point_ = array_->point(lane_);
  if (!point_.function) throw std::invalid_argument("CamLawLane: the array gives no point function");
}

CamLawLane::~CamLawLane() = default;

std::vector<double> CamLawLane::breakpoints() const {
  const std::span<const double> b = array_->breakpoints(lane_);
  return {b.begin(), b.end()};
}

bool CamLawLane::higher_derivatives(double phi, double& d4, double& d5) const {
  return array_->higher_derivatives(lane_, phi, d4, d5);
}

bool CamLawLane::monotone_breaks(int order, std::vector<double>& breaks) const {
  return array_->monotone_breaks(lane_, order, breaks);
}

bool CamLawLane::lift_integrals(double a, double b, double& integral, double& integral_of_square) const {
  return array_->lift_integrals(lane_, a, b, integral, integral_of_square);
}

const CamLawArray* lanes_of(const CamLawBlock& block) {
  // Lane k for case k of one array: a consumer then reads case k's figures at index k of the
  // columns. A block of one law for every case (size 1) qualifies only as lane 0.
  const CamLawArray* array = nullptr;
  bool any = false;
  for (std::size_t k = 0; k < block.size(); ++k) {
    const std::shared_ptr<const CamLaw>& law = block.shared(k);
    if (!law) continue;  // a failed case
    const auto* lane = dynamic_cast<const CamLawLane*>(law.get());
    if (!lane || lane->lane() != k) return nullptr;
    if (any && &lane->array() != array) return nullptr;
    array = &lane->array();
    any = true;
  }
  return array;
}

}  // namespace mechgraph
