#pragma once
// Internal clearance of a radial spherical plain bearing, steel/steel, requiring maintenance
// (GE..E / GE..ES, dimension series E of ISO 12240-1) — methods/backlash.md, "Joint types".
//
// Radial internal clearance: the distance the inner ring can move radially relative to the
// outer ring from one extreme position to the opposite one, unmounted. ISO 12240-1 groups it
// as C2 (< normal), normal (CN) and C3 (> normal) by bore d; the table is data (see the .cpp
// for the source of every number).
//
// Axial internal clearance from the sphere geometry (our derivation, not a catalogue relation;
// the catalogues only say it depends on the geometry and is several times the radial one):
// inner sphere radius Ri = dk/2, outer ring sphere radius Ro = Ri + cr/2 (radial clearance cr),
// the outer ring's sphere is a band of width C (outer ring width) centred on the sphere centre.
// Moving the inner ring axially by a, the nearest outer-surface point to its centre is the band
// edge (rho, C/2): distance^2 = Ro^2 - a C + a^2. Contact when that equals Ri^2:
//   a^2 - C a + (Ro^2 - Ri^2) = 0  ->  a = (C - sqrt(C^2 - 4 D)) / 2,  D = Ro^2 - Ri^2 = (cr/2)(dk + cr/2)
// and the axial clearance (extreme to extreme) is
//   ca = 2a = 4 D / (C + sqrt(C^2 - 4 D))       (written without cancellation)
//      ~ cr dk / C for cr << C                  (e.g. GE 40 ES: dk 52.4, C 22 -> ca ~ 2.4 cr).
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph::joints {

enum class ClearanceGroup { c2, normal, c3 };

/// "C2", "normal", "C3" (the scene's choice names).
std::string_view to_string(ClearanceGroup g);
/// The group of a choice name; throws NodeError("clearance_group") for anything else.
ClearanceGroup clearance_group_from(std::string_view name);
/// The designation used in labels: C2, CN, C3.
std::string_view designation(ClearanceGroup g);

struct ClearanceRange {
  double min = 0.0;  // m
  double max = 0.0;  // m
};

/// One row of the table: bores over `bore_over` up to and including `bore_incl` (m).
struct RadialClearanceRow {
  double bore_over;
  double bore_incl;
  ClearanceRange c2, normal, c3;
  const ClearanceRange& of(ClearanceGroup g) const;
};

/// The rows, in increasing bore.
const std::vector<RadialClearanceRow>& radial_clearance_table();

/// The radial internal clearance of group `g` for bore `d` (m). Throws NodeError("bore") listing
/// the covered range when d is outside the table.
ClearanceRange radial_internal_clearance(double d, ClearanceGroup g);

/// Axial internal clearance (m, extreme to extreme) allowed by the radial clearance `radial` (m)
/// for ball diameter `dk` and outer ring width `C` (formula above). Throws NodeError naming
/// `ball_diameter` or `outer_ring_width` for impossible geometry (C >= dk, or a clearance so
/// large that the ball would slip out of the outer ring's band).
double axial_internal_clearance(double radial, double dk, double C);

}  // namespace mechgraph::joints
