#pragma once
// Cam laws over arrays of cases (docs/design/sdk-1.6-laws-over-arrays.md): one law family (one law
// type with its choices fixed) over the cases of a block, its constants held as columns, so that a
// consumer can evaluate many points of many cases in one call instead of one virtual call a point.
//
// The array travels inside ordinary laws: a CamLawBlock (final, frozen) whose every live case k
// holds a CamLawLane, lane k of one array. A consumer that knows nothing of arrays sees plain
// CamLaw objects and works as before; one that does asks lanes_of(block) and, when it answers,
// evaluates through the array. Every answer of a lane comes from its array (CamLawLane below is
// the one implementation), so a lane cannot disagree with its array; the array must give, for each
// lane, exactly the bits the scalar law of the same parameters gives (the producer's tests say so,
// and the rows of a sweep are byte for byte those of the per-case path).
//
// The CamLaw contract holds lane by lane: evaluate() is asked only for angles strictly inside the
// lane's event, and the host checks every lane (CamLaw::contract_problem) as it checks every law.
#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/domain/cam_law_block.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace mechgraph {

/// The figures of every lane, each a column of lanes() values (not owned: the array keeps them).
struct CamLawColumns {
  const double* event_begin = nullptr;    // rad
  const double* event_end = nullptr;      // rad
  const double* max_lift = nullptr;       // m
  const double* base_radius = nullptr;    // m
  const double* roller_radius = nullptr;  // m; 0 for a flat-faced tappet
};

class MECHGRAPH_INTERFACE CamLawArray {
 public:
  virtual ~CamLawArray();  // out of line (key function, sdk/src/cam_law_array.cpp)
  /// The number of lanes; lane k is case k of the block the array was made for. A case the
  /// producer refused has a lane no law points at: its values are not to be read.
  virtual std::size_t lanes() const = 0;
  virtual CamLawColumns columns() const = 0;
  /// n points: point k at angle phi[k] on lane lane[k] (lane k when `lane` is null), each strictly
  /// inside its lane's event, into out[k]: the same bits that lane's law gives at that angle.
  virtual void evaluate(const std::uint32_t* lane, const double* phi, std::size_t n, LiftDerivatives* out) const = 0;
  /// One point of one lane, evaluate() of one, as a plain function and the lane's data it reads:
  /// point(k).function(point(k).data, phi). A lane's evaluate_in_event calls it directly, one
  /// indirect call a point. Valid, and the same, for the array's whole life.
  struct Point {
    LiftDerivatives (*function)(const void* data, double phi) = nullptr;
    const void* data = nullptr;
  };
  virtual Point point(std::size_t lane) const = 0;
  /// The lane's breakpoints (CamLaw::breakpoints), kept by the array.
  virtual std::span<const double> breakpoints(std::size_t lane) const = 0;
  /// The lane's answers to the optional queries of CamLaw, with the same meaning.
  virtual bool higher_derivatives(std::size_t lane, double phi, double& d4, double& d5) const = 0;
  virtual bool monotone_breaks(std::size_t lane, int order, std::vector<double>& breaks) const = 0;
  virtual bool lift_integrals(std::size_t lane, double a, double b, double& integral, double& integral_of_square) const = 0;
};

/// Lane `lane` of an array, seen as a law: every answer is its array's. Final: no producer can make
/// a lane answer otherwise.
class MECHGRAPH_INTERFACE CamLawLane final : public CamLaw {
 public:
  /// Throws std::out_of_range when `lane` is not below array->lanes(), std::invalid_argument when
  /// `array` is null.
  CamLawLane(std::shared_ptr<const CamLawArray> array, std::size_t lane);
  ~CamLawLane() override;  // out of line (key function)

  double event_begin() const override { return columns_.event_begin[lane_]; }
  double event_end() const override { return columns_.event_end[lane_]; }
  LiftDerivatives evaluate_in_event(double phi) const override { return point_.function(point_.data, phi); }
  std::vector<double> breakpoints() const override;
  double max_lift() const override { return columns_.max_lift[lane_]; }
  double base_radius() const override { return columns_.base_radius[lane_]; }
  double roller_radius() const override { return columns_.roller_radius[lane_]; }
  bool higher_derivatives(double phi, double& d4, double& d5) const override;
  bool monotone_breaks(int order, std::vector<double>& breaks) const override;
  bool lift_integrals(double a, double b, double& integral, double& integral_of_square) const override;

  const CamLawArray& array() const { return *array_; }
  std::size_t lane() const { return lane_; }

 private:
  std::shared_ptr<const CamLawArray> array_;
  CamLawColumns columns_;                 // the array's, read once
  CamLawArray::Point point_;              // the array's, read once
  std::size_t lane_;
};

/// The array behind a block of laws when every case that holds a law holds lane k of one array
/// (k its case), else null: then the block's laws are to be asked one by one, as plain laws.
const CamLawArray* lanes_of(const CamLawBlock& block);

}  // namespace mechgraph
