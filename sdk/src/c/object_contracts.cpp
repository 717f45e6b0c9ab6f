// The contract checks of mg_check_object for mechgraph.valve_motion/1, mechgraph.follower/1 and
// mechgraph.joint_play/1 (object_contracts.hpp).
#include "object_contracts.hpp"

#include <mechgraph/c/domain/cam_law.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <charconv>
#include <sstream>
#include <vector>

namespace mechgraph::c_checks {
namespace {

// Six significant digits, whatever locale the host has set (to_chars knows none).
std::string number(double value) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 6);
  return std::string(buffer, ec == std::errc() ? end : buffer);
}

std::string degrees(double rad) { return number(rad * 180.0 / std::numbers::pi) + " deg"; }

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

// The valve's lift at phi: finite with its derivatives and not below the floor, else the problem.
std::string lift_problem(const mg_object* object, const mg_valve_motion_v1* t, double phi, double floor) {
  mg_lift4 d{};
  const mg_status s = t->at(object, phi, &d);
  if (s != MG_OK) return "at(" + degrees(phi) + ") failed with status " + std::to_string(s);
  if (!std::isfinite(d.h) || !std::isfinite(d.dh) || !std::isfinite(d.d2h) || !std::isfinite(d.d3h))
    return "a NaN or infinite valve lift or derivative at " + degrees(phi);
  if (d.h < floor) return "a negative valve lift (" + number(d.h) + " m) at " + degrees(phi);
  return {};
}

}  // namespace

std::string valve_motion_problem(const mg_object* object, const mg_valve_motion_v1* t) {
  if (t->struct_size < sizeof(mg_valve_motion_v1) || !t->at || !t->at_many || !t->camshaft_speed || !t->open_period ||
      !t->knots || !t->rocker_ratio || !t->lash || !t->cam)
    return "its mechgraph.valve_motion/1 table is incomplete (a function missing or struct_size too small)";
  if (const double w = t->camshaft_speed(object); !positive(w))
    return "camshaft_speed() is " + number(w) + " rad/s, not a positive finite speed";
  if (const double r = t->rocker_ratio(object); !positive(r)) return "rocker_ratio() is " + number(r) + ", not positive and finite";
  if (const double l = t->lash(object); !std::isfinite(l) || l < 0.0)
    return "lash() is " + number(l) + " m, negative or not finite";
  double begin = 0.0, end = 0.0;
  t->open_period(object, &begin, &end);
  if (!std::isfinite(begin) || !std::isfinite(end)) return "its open period's bounds are not finite";
  if (!(begin < end)) return "its open period is empty (opens at " + degrees(begin) + ", closes at " + degrees(end) + ")";
  // Two calls: the count, then the fill.
  const std::size_t n = t->knots(object, nullptr, 0);
  if (n < 2) return "knots() gives " + std::to_string(n) + " angles; it must give at least the open period's begin and end";
  std::vector<double> knots(n);
  knots.resize(std::min(n, t->knots(object, knots.data(), n)));
  if (knots.size() < 2 || knots.front() != begin || knots.back() != end)
    return "knots() does not run from the open period's begin (" + degrees(begin) + ") to its end (" + degrees(end) + ")";
  for (std::size_t i = 1; i < knots.size(); ++i)
    if (!(knots[i] > knots[i - 1]))
      return "knots() are not ascending without repeats (" + degrees(knots[i]) + " after " + degrees(knots[i - 1]) + ")";
  const mg_object* cam = t->cam(object);
  if (!cam || !cam->vtbl || !cam->vtbl->query || !cam->vtbl->query(cam, MG_CAM_LAW, 1))
    return "cam() gives no object answering mechgraph.cam_law version 1";
  // The lift: 16 angles across the period, then each piece's midpoint (as the cam law's check).
  std::vector<double> angles;
  constexpr int uniform = 16;
  for (int i = 0; i < uniform; ++i) angles.push_back(begin + (end - begin) * (i + 0.5) / uniform);
  for (std::size_t i = 1; i < knots.size(); ++i) angles.push_back(0.5 * (knots[i - 1] + knots[i]));
  double peak = 0.0;
  for (double phi : angles) {
    mg_lift4 d{};
    if (t->at(object, phi, &d) == MG_OK && std::isfinite(d.h)) peak = std::max(peak, std::abs(d.h));
  }
  for (double phi : angles)
    if (std::string p = lift_problem(object, t, phi, -1e-9 * peak); !p.empty()) return p;
  return {};
}

std::string follower_problem(const mg_object* object, const mg_follower_v1* t) {
  if (t->struct_size < sizeof(mg_follower_v1) || !t->type_name || !t->describe || !t->roller_radius || !t->pivoted ||
      !t->cam_lever || !t->contact)
    return "its mechgraph.follower/1 table is incomplete (a function missing or struct_size too small)";
  std::string name;
  t->type_name(object, mg_text_sink{&name, [](void* self, const char* text, size_t size) {
                                      if (text) static_cast<std::string*>(self)->append(text, size);
                                    }});
  if (name.empty()) return "type_name() gives no name (the node type that made it, for messages)";
  if (const double r = t->roller_radius(object); !std::isfinite(r) || r < 0.0)
    return "roller_radius() is " + number(r) + " m, negative or not finite (0 for a flat face)";
  if (const int32_t p = t->pivoted(object); p != 0 && p != 1) return "pivoted() is " + std::to_string(p) + ", not 0 or 1";
  return {};
}

std::string joint_play_problem(const mg_object* object, const mg_joint_play_v1* t) {
  if (t->struct_size < sizeof(mg_joint_play_v1) || !t->data)
    return "its mechgraph.joint_play/1 table is incomplete (a function missing or struct_size too small)";
  mg_joint_play_data_v1 data{};
  t->data(object, &data);
  if (!data.joint || !*data.joint) return "its data names no joint";
  if (data.term_count == 0 || !data.terms) return "joint '" + std::string(data.joint) + "' has no play terms";
  for (std::size_t i = 0; i < data.term_count; ++i) {
    const mg_play_term& term = data.terms[i];
    const std::string where = "term " + std::to_string(i) + (term.label ? " ('" + std::string(term.label) + "')" : "");
    if (!term.label) return where + " has no label";
    if (term.link_count > 0 && !term.links) return where + " has " + std::to_string(term.link_count) + " links but no array of them";
    for (std::size_t k = 0; k < term.link_count; ++k) {
      const mg_tolerance_link& l = term.links[k];
      const std::string link = "link " + std::to_string(k) + (l.label ? " ('" + std::string(l.label) + "')" : "") + " of " + where;
      if (!l.label) return link + " has no label";
      if (!std::isfinite(l.mean) || !std::isfinite(l.sensitivity)) return link + ": its mean or sensitivity is not finite";
      if (!std::isfinite(l.half_range) || l.half_range < 0.0)
        return link + ": its half range is " + number(l.half_range) + ", negative or not finite";
      if (l.distribution != MG_DISTRIBUTION_NORMAL && l.distribution != MG_DISTRIBUTION_UNIFORM &&
          l.distribution != MG_DISTRIBUTION_TRIANGULAR)
        return link + ": its distribution " + std::to_string(l.distribution) + " is none of MG_DISTRIBUTION_*";
    }
  }
  return {};
}

}  // namespace mechgraph::c_checks
