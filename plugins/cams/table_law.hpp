#pragma once
// cam.table: a tabulated lift (measured, or exported by another tool) read from CSV, interpolated
// by a quintic spline whose derivatives are the exact derivatives of the interpolant.
// See docs/methods/valvetrain.md, stage 1 ("a tabulated lift ... read from CSV").
//
// File: one row per line, two columns: cam angle from the nose, lift (units from the node's
// angle_unit / lift_unit, default deg and mm). Columns separated by ',' or ';' (or, with neither,
// by blanks). '#' starts a comment; blank lines are skipped; one header line before the first row
// is allowed. The angles must increase strictly and the lift must not be negative; every error
// names file:line.
//
// Lift event: leading and trailing rows of zero lift (the base circle) are dropped except the last
// leading and the first trailing one; the event runs between those two rows, which must therefore
// have zero lift, and it must lie within -180 .. 180 deg.
//
// Interpolant: the quintic (degree 5) B-spline interpolating every row, with the not-a-knot end
// conditions of de Boor (interior knots at rows 3 .. n-4, so the first and last three intervals are
// one polynomial each): C4 inside the event, so no breakpoints inside it; it reproduces any
// polynomial of degree <= 5 exactly. Needs at least 6 rows in the event. Built by collocation
// (de Boor, A Practical Guide to Splines, ch. IX and XIII: the collocation matrix is totally
// positive, banded elimination without pivoting is stable), converted to Taylor coefficients per
// interval by differencing the B-spline coefficients. Boost 1.74's interpolators give at most the
// second derivative, the CamLaw contract needs the third. Between rows the interpolant can
// overshoot the data slightly (as any smooth interpolant does near a kink in the data).
#include "cam_node.hpp"

#include <mechgraph/domain/cam_law.hpp>

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph::cams {

/// One row of a lift table in SI, with the line of the file it came from.
struct LiftTableRow {
  double angle = 0.0;  // rad from the nose
  double lift = 0.0;   // m
  int line = 0;
};

struct LiftTable {
  std::string source;  // file name, for messages
  std::vector<LiftTableRow> rows;
};

/// Parses the text of a lift table (angles times angle_scale -> rad, lifts times lift_scale -> m).
/// Throws NodeError("file", "source:line: ...") on a bad row, non-increasing angle or negative lift.
LiftTable parse_lift_table(std::string_view text, const std::string& source, double angle_scale, double lift_scale);

/// The largest lift table read: 64 MiB (a million rows are some 20 MB).
inline constexpr std::size_t lift_table_limit = std::size_t{64} << 20;

/// Reads and parses a lift table file (a relative path is taken from the working directory).
/// Only a regular file of at most lift_table_limit bytes is read (mechgraph/bounded_read.hpp);
/// anything else is NodeError("file", ...) naming the path and why.
LiftTable read_lift_table(const std::string& path, double angle_scale, double lift_scale);

/// The interpolated table as a CamLaw.
class TableLaw final : public CamLaw {
 public:
  /// Checks and trims the table as described above; throws NodeError("file", "source:line: ...").
  TableLaw(const LiftTable& table, double base_radius);

  double event_begin() const override { return breaks_.front(); }
  double event_end() const override { return breaks_.back(); }
  LiftDerivatives evaluate_in_event(double phi) const override;
  /// None: the interpolant is C4 inside the event.
  std::vector<double> breakpoints() const override { return {}; }
  /// Maximum of the interpolant over the event (found by sampling and Brent's method).
  double max_lift() const override { return max_lift_; }
  double base_radius() const override { return base_radius_; }

  /// Angle where the interpolant is largest.
  double max_lift_angle() const { return max_lift_angle_; }
  /// Lines of the file where the event begins and ends.
  int first_line() const { return first_line_; }
  int last_line() const { return last_line_; }
  /// Angles of the rows kept (the event's rows), rad.
  const std::vector<double>& row_angles() const { return row_angles_; }

 private:
  std::vector<double> breaks_;               // polynomial pieces: [breaks_[i], breaks_[i+1]]
  std::vector<std::array<double, 6>> taylor_;  // h^(r)(breaks_[i]) / r!, r = 0..5
  std::vector<double> row_angles_;
  double base_radius_ = 0.0;
  double max_lift_ = 0.0;
  double max_lift_angle_ = 0.0;
  int first_line_ = 0;
  int last_line_ = 0;
};

/// The cam.table node's law: params `file`, `angle_unit`, `lift_unit`; checks the table against
/// the common params (the event span must equal action_angle within 1e-4 deg, the interpolant's
/// maximum must equal max_lift within 0.1 %), each mismatch a NodeError naming that parameter.
CamLawDefinition table_law_definition();

}  // namespace mechgraph::cams
