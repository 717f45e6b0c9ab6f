#pragma once
// The contract checks mg_check_object runs on an object of an SDK interface other than the cam
// law (whose checks are CamLaw::contract_problem's): each returns what the object breaks, in words
// a plugin author can act on, or an empty string. Cheap: a look at the table, the plain data and
// a few dozen evaluations at most, as the checks the host runs on a C++ object a node outputs.
#include <mechgraph/c/domain/follower.h>
#include <mechgraph/c/domain/joint_play.h>
#include <mechgraph/c/domain/valve_motion.h>

#include <string>

namespace mechgraph::c_checks {

/// mechgraph.valve_motion/1: the table complete; camshaft speed, rocker ratio positive and finite,
/// lash finite and not negative; the open period finite and not empty; the knots ascending from
/// its begin to its end; a cam law; the lift and its derivatives finite and the lift not negative
/// at 16 angles and in each piece.
std::string valve_motion_problem(const mg_object* object, const mg_valve_motion_v1* table);

/// mechgraph.follower/1: the table complete; a type name; the roller radius finite and not
/// negative; `pivoted` 0 or 1.
std::string follower_problem(const mg_object* object, const mg_follower_v1* table);

/// mechgraph.joint_play/1: the table complete; the joint named; at least one term; every term and
/// link labelled, each link's mean, half range (not negative) and sensitivity finite, its
/// distribution one of MG_DISTRIBUTION_*.
std::string joint_play_problem(const mg_object* object, const mg_joint_play_v1* table);

}  // namespace mechgraph::c_checks
