#pragma once
// cam.program: a cam built from segments, each a rise, a dwell or a return over its own cam angle
// with its own normalised law (rise_law.hpp), so rise and return may differ in angle and law and a
// dwell may hold the top (docs/methods/valvetrain.md, "A cam built from segments"). The segments
// follow each other from the start of lift; the event is centred on cam angle 0. On segment k of
// angle beta_k starting at phi_k at height H_k, with x = (phi - phi_k)/beta_k:
//   rise    h = H_k + L_k s(x),  h^(n) = L_k s^(n)(x) / beta_k^n
//   return  h = H_k - L_k s(x),  h^(n) = -L_k s^(n)(x) / beta_k^n
//   dwell   h = H_k
// At every joint (and where the event meets the base circle) the one-sided values are compared:
// the joint report says which derivative jumps there and by how much.
#include "cam_node.hpp"
#include "rise_law.hpp"

#include <mechgraph/domain/cam_law.hpp>

#include <string>
#include <vector>

namespace mechgraph::cams {

struct CamSegment {
  enum class Kind { rise, dwell, ret } kind = Kind::rise;
  double angle = 0.0;  // rad
  double lift = 0.0;   // m, rise and return
  RiseShape shape = RiseShape::cycloidal;
};

/// What happens at one joint: the derivatives' jumps (right minus left) and the first that jumps.
struct SegmentJoint {
  double angle = 0.0;  // rad
  std::string between;  // "rise 1 / dwell 2", "base circle / rise 1"
  double jump[4] = {0.0, 0.0, 0.0, 0.0};  // lift, velocity, acceleration, jerk
  int first_jump = 4;  // 0 lift ... 3 jerk; 4: continuous up to the jerk
};

class ProgramLaw final : public CamLaw {
 public:
  /// Throws NodeError("segments", ...) for an empty program, a total angle of 360 deg or more, a
  /// lift that would go below zero or does not end at zero, or a rise/return without lift.
  ProgramLaw(std::vector<CamSegment> segments, double base_radius);

  double event_begin() const override { return begin_; }
  double event_end() const override { return end_; }
  LiftDerivatives evaluate_in_event(double phi) const override;
  std::vector<double> breakpoints() const override;
  double max_lift() const override { return max_lift_; }
  double base_radius() const override { return base_radius_; }

  /// The joints, event start and end included, with their jumps.
  std::vector<SegmentJoint> joints() const;

 private:
  LiftDerivatives on_segment(std::size_t k, double x) const;  // x in [0, 1]

  std::vector<CamSegment> segments_;
  std::vector<double> start_;   // phi_k
  std::vector<double> height_;  // H_k
  double begin_ = 0.0, end_ = 0.0, max_lift_ = 0.0, base_radius_ = 0.0;
};

std::string segment_kind_name(CamSegment::Kind k);

/// The node type's description (registered in standard_laws.cpp).
CamLawDefinition program_law_definition();

}  // namespace mechgraph::cams
