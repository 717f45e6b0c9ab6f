#include "spherical_clearance.hpp"

#include <mechgraph/errors.hpp>

#include <cmath>
#include <sstream>

namespace mechgraph::joints {

std::string_view to_string(ClearanceGroup g) {
  switch (g) {
    case ClearanceGroup::c2: return "C2";
    case ClearanceGroup::normal: return "normal";
    case ClearanceGroup::c3: return "C3";
  }
  return "?";
}

std::string_view designation(ClearanceGroup g) {
  switch (g) {
    case ClearanceGroup::c2: return "C2";
    case ClearanceGroup::normal: return "CN";
    case ClearanceGroup::c3: return "C3";
  }
  return "?";
}

ClearanceGroup clearance_group_from(std::string_view name) {
  for (ClearanceGroup g : {ClearanceGroup::c2, ClearanceGroup::normal, ClearanceGroup::c3})
    if (name == to_string(g)) return g;
  throw NodeError("clearance_group", "unknown clearance group '" + std::string(name) + "'; valid groups are C2, normal, C3");
}

const ClearanceRange& RadialClearanceRow::of(ClearanceGroup g) const {
  switch (g) {
    case ClearanceGroup::c2: return c2;
    case ClearanceGroup::normal: return normal;
    case ClearanceGroup::c3: return c3;
  }
  return normal;
}

namespace {

// Radial internal clearance of steel/steel radial spherical plain bearings, dimension series E
// (GE..E, GE..ES), by bore d, in micrometres, groups C2 / normal / C3 of ISO 12240-1.
// Source: the radial clearance table of the ZVL (Slovakia) catalogue page for GE spherical plain
// bearings (zvlslovakia.bg, "Spherical plain bearings", "Radial clearance"), rows d over 12 up to
// 240 mm; the same values appear in SKF's table for metric GE bearings, which SKF states follow
// ISO 12240-1:1998, and Schaeffler groups the clearance "in accordance with DIN ISO 12240-1".
// Only rows read from a retrieved copy are held: the standard's rows for d <= 12 mm and
// 240 < d <= 300 mm are left out until checked against a copy (give radial_clearance_min/_max
// for those bores).
struct RowUm {
  double over, incl, c2_min, c2_max, n_min, n_max, c3_min, c3_max;
};
constexpr RowUm rows_um[] = {
    // d over, incl (mm) |  C2     | normal   |  C3
    {12, 20, 10, 40, 40, 82, 82, 124},
    {20, 35, 12, 50, 50, 100, 100, 150},
    {35, 60, 15, 60, 60, 120, 120, 180},
    {60, 90, 18, 72, 72, 142, 142, 212},
    {90, 140, 18, 85, 85, 165, 165, 245},
    {140, 240, 18, 100, 100, 192, 192, 284},
};

std::vector<RadialClearanceRow> build_table() {
  std::vector<RadialClearanceRow> table;
  for (const RowUm& r : rows_um)
    table.push_back({r.over * 1e-3, r.incl * 1e-3, {r.c2_min * 1e-6, r.c2_max * 1e-6},
                     {r.n_min * 1e-6, r.n_max * 1e-6}, {r.c3_min * 1e-6, r.c3_max * 1e-6}});
  return table;
}

// Bores are compared in whole micrometres so that "20 mm" parsed from a scene (0.02 up to a
// rounding) lands in the row "over 12 incl. 20", never in the next one.
long micrometres(double metres) { return std::lround(metres * 1e6); }

}  // namespace

const std::vector<RadialClearanceRow>& radial_clearance_table() {
  static const std::vector<RadialClearanceRow> table = build_table();
  return table;
}

ClearanceRange radial_internal_clearance(double d, ClearanceGroup g) {
  const auto& table = radial_clearance_table();
  if (std::isfinite(d)) {
    const long d_um = micrometres(d);
    for (const RadialClearanceRow& row : table)
      if (d_um > micrometres(row.bore_over) && d_um <= micrometres(row.bore_incl)) return row.of(g);
  }
  std::ostringstream msg;
  msg << "bore " << d * 1e3 << " mm is outside the ISO 12240-1 radial internal clearance table held here, which covers "
      << table.front().bore_over * 1e3 << " mm < d <= " << table.back().bore_incl * 1e3
      << " mm; give radial_clearance_min and radial_clearance_max from the bearing's catalogue instead";
  throw NodeError("bore", msg.str());
}

double axial_internal_clearance(double radial, double dk, double C) {
  if (!(C < dk)) {
    std::ostringstream msg;
    msg << "outer ring width " << C * 1e3 << " mm must be smaller than the ball diameter dk = " << dk * 1e3 << " mm";
    throw NodeError("outer_ring_width", msg.str());
  }
  const double half = 0.5 * radial;
  const double D = half * (dk + half);  // Ro^2 - Ri^2
  const double disc = C * C - 4.0 * D;
  if (!(disc >= 0.0)) {
    std::ostringstream msg;
    msg << "a radial clearance of " << radial * 1e6 << " um lets the ball (dk = " << dk * 1e3
        << " mm) slip axially out of an outer ring " << C * 1e3 << " mm wide: needs (cr/2)(dk + cr/2) <= C^2/4";
    throw NodeError("outer_ring_width", msg.str());
  }
  return 4.0 * D / (C + std::sqrt(disc));
}

}  // namespace mechgraph::joints
