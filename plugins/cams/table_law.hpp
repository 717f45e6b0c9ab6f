#pragma once
// cam.table: a tabulated lift (measured, or exported by another tool) read from CSV, interpolated
// by a quintic spline whose derivatives are the exact derivatives of the spline, or, for a measured
// table, smoothed by a penalised quintic spline (smoothing_spline.hpp). See
// docs/methods/valvetrain.md, stage 1 ("a tabulated lift ... read from CSV") and "Measured lift
// tables".
//
// File: one row per line, two columns: cam angle from the nose, lift (units from the node's
// angle_unit / lift_unit, default deg and mm). Columns separated by ',' or ';' (or, with neither,
// by blanks). '#' starts a comment; blank lines are skipped; one header line before the first row
// is allowed. The angles must increase strictly and the lift must not be negative; every error
// names file:line.
//
// Lift event: leading and trailing rows of zero lift (the base circle) are dropped except the last
// leading and the first trailing one; the event runs between those two rows, which must therefore
// have zero lift, and it must lie within -180 .. 180 deg. Needs at least 6 rows in the event.
//
// Interpolant (smoothing none): the quintic (degree 5) B-spline interpolating every row, with the
// not-a-knot end conditions of de Boor (quintic_spline.hpp): C4 inside the event, so no
// breakpoints inside it; it reproduces any polynomial of degree <= 5 exactly. Boost 1.74's
// interpolators give at most the second derivative, the CamLaw contract needs the third. Between
// rows the interpolant can overshoot the data slightly (as any smooth interpolant does near a kink
// in the data), and it follows every digit of the rows: rounding to a last printed digit r shows in
// h'' and h''' amplified by about 1/step^2 and 1/step^3.
//
// Smoothing (smoothing resolution or gcv): the penalised quintic spline with a knot at every row,
// zero at the event's ends, B-spline coefficients >= 0 (so the lift is >= 0); lambda from the
// resolution (residual RMS = r / sqrt(12), the RMS of rounding to r) or by generalised
// cross-validation. Also C4 inside the event.
#include "cam_node.hpp"
#include "quintic_spline.hpp"
#include "smoothing_spline.hpp"

#include <mechgraph/domain/cam_law.hpp>

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
  double lift_scale = 1.0;  // m per unit of the file's lift column (to read its printed digits)
};

/// Parses the text of a lift table (angles times angle_scale -> rad, lifts times lift_scale -> m).
/// Throws NodeError("file", "source:line: ...") on a bad row, non-increasing angle or negative lift.
LiftTable parse_lift_table(std::string_view text, const std::string& source, double angle_scale, double lift_scale);

/// The table given as lists (params `angles` in rad and `lifts` in m, as long as each other): row
/// i is "line" i + 1 in messages. TableLaw makes the same checks as for a file's rows.
LiftTable listed_lift_table(const ParamSet& params);

/// The largest lift table read: 64 MiB (a million rows are some 20 MB).
inline constexpr std::size_t lift_table_limit = std::size_t{64} << 20;

/// Reads and parses a lift table file (a relative path is taken from the working directory).
/// Only a regular file of at most lift_table_limit bytes is read (mechgraph/bounded_read.hpp);
/// anything else is NodeError("file", ...) naming the path and why.
LiftTable read_lift_table(const std::string& path, double angle_scale, double lift_scale);

/// The quantum of the table's lifts as printed: the largest of 1, 0.1, ..., 1e-6 units of the
/// file's lift column of which every lift is a whole multiple, in m; 0 if none is, or if fewer than
/// 8 rows have lift (then the resolution cannot be read from the file).
double lift_quantum(const LiftTable& table);

enum class TableSmoothing { none, resolution, gcv };

struct TableSmoothingRequest {
  TableSmoothing method = TableSmoothing::none;
  double resolution = 0.0;  // m, the last printed digit of the lift; 0: not stated (then lift_quantum)
};

/// What the law found in its data and what the smoothing did. Lengths in m, angles in rad.
struct TableDiagnostics {
  int rows = 0;              // rows of the event, its two zero ends included
  double row_step = 0.0;     // median angle step between the rows
  double resolution = 0.0;   // stated, else detected (lift_quantum); 0 unknown
  bool resolution_detected = false;
  // Share of neighbouring rows of the event whose lifts differ by less than half the resolution
  // (the same printed value): rows closer than the resolution tells apart, whose rounding errors
  // are a staircase, not independent noise. 0 when no resolution is known.
  double same_lift_share = 0.0;
  // Rows minus law over the inner rows of the event (the ends are held at zero).
  double residual_rms = 0.0;
  double residual_max = 0.0;  // largest |row - law|
  double residual_max_angle = 0.0;
  int residual_max_line = 0;
  // Smoothing only: lambda (dimensionless, smoothing_spline.hpp), effective degrees of freedom,
  // whether lambda sits at an end of its range, B-spline coefficients held at zero for lift >= 0.
  double lambda = 0.0;
  double dof = 0.0;
  bool lambda_at_limit = false;
  int held_at_zero = 0;
  // max |h''| and |h'''| of the law over the event.
  double max_abs_acceleration = 0.0;
  double max_jerk = 0.0;
  // The noise the resolution alone puts into h'' and h''': their RMS over the event for the same
  // interpolant or smoother applied to a pattern of rounding errors (uniform in +-r/2, fixed seed)
  // at the table's rows. Zero when no resolution is known.
  double noise_resolution = 0.0;           // r behind them: stated, detected, or GCV's estimate
  bool noise_resolution_estimated = false;  // r = sqrt(12) sigma, sigma^2 = RSS / (m' - dof) (GCV)
  double acceleration_noise = 0.0;
  double jerk_noise = 0.0;
  SmoothingWork work;
};

/// The interpolated or smoothed table as a CamLaw.
class TableLaw final : public CamLaw {
 public:
  /// Checks and trims the table as described above; throws NodeError("file", "source:line: ...");
  /// smoothing resolution with no resolution stated or detectable is NodeError("resolution", ...).
  TableLaw(const LiftTable& table, double base_radius, const TableSmoothingRequest& smoothing = {});

  double event_begin() const override { return pieces_.breaks.front(); }
  double event_end() const override { return pieces_.breaks.back(); }
  LiftDerivatives evaluate_in_event(double phi) const override;
  /// The spline's own knots: the interpolant and the smoothing spline are C4 inside the event, but
  /// their fifth derivative jumps at every knot, so h'' is only C2 there and no single polynomial
  /// follows it across them. Declared, the certified searches (docs/methods/numerics.md) take each
  /// quintic piece as its own smooth piece and resolve it exactly.
  std::vector<double> breakpoints() const override {
    return std::vector<double>(pieces_.breaks.begin() + 1, pieces_.breaks.end() - 1);
  }
  /// Maximum of the law over the event (found by sampling and Brent's method).
  double max_lift() const override { return max_lift_; }
  double base_radius() const override { return base_radius_; }

  /// Angle where the law is largest.
  double max_lift_angle() const { return max_lift_angle_; }
  /// Lines of the file where the event begins and ends.
  int first_line() const { return first_line_; }
  int last_line() const { return last_line_; }
  /// Angles (rad) and lifts (m) of the rows kept (the event's rows).
  const std::vector<double>& row_angles() const { return row_angles_; }
  const std::vector<double>& row_lifts() const { return row_lifts_; }
  TableSmoothing smoothing() const { return method_; }
  const TableDiagnostics& diagnostics() const { return diagnostics_; }
  /// What the diagnostics mean, as lines for out.note(): the smoothing done; a resolution too
  /// coarse for the curvature and jerk of the unsmoothed table; residuals beyond the resolution.
  std::vector<std::string> notes() const;

 private:
  std::string source_;
  QuinticPieces pieces_;  // the law over the event
  std::vector<double> row_angles_, row_lifts_;
  TableSmoothing method_ = TableSmoothing::none;
  TableDiagnostics diagnostics_;
  double base_radius_ = 0.0;
  double max_lift_ = 0.0;
  double max_lift_angle_ = 0.0;
  int first_line_ = 0;
  int last_line_ = 0;
};

/// The cam.table node's law: params `file`, `angle_origin`, `angle_unit`, `lift_unit`,
/// `smoothing`, `resolution`, optional input `master` (a cam law to compare with); checks the table
/// against the common params (the event span must equal action_angle within 1e-4 deg, the law's
/// maximum must equal max_lift within 0.1 %), each mismatch a NodeError naming that parameter.
/// Extra outputs: residuals, max_jerk, the smoothing's lambda and degrees of freedom, the noise
/// estimates, and with a master the deviation from it.
CamLawDefinition table_law_definition();

}  // namespace mechgraph::cams
