#pragma once
// The joint node types of this plugin and the contract they share (docs/methods/backlash.md,
// "Joint types as plugins").
//
// Every joint outputs
//   play       a JointPlay handle: its PlayTerms along the joint's line of action, each labelled
//              with its node-independent source (a fit designation, "radial internal clearance
//              C3, bore 20 mm", "trunnion end float 50 um");
//   play_min   sum over terms of max(0, lower limit of the term)     (worst case, m)
//   play_max   sum over terms of max(0, upper limit of the term)     (worst case, m)
//   play_mean  sum over terms of max(0, mean of the untruncated term) (m).
// play_mean clips each term's *mean* at zero; it is not the expectation of the truncated play
// (E[max(0, X)] >= max(0, E[X])), which the statistical stackers compute from the terms. So an
// interference fit contributes 0 to all three, and a transition fit with a negative mean
// contributes 0 to play_mean but its positive upper limit to play_max.
#include <mechgraph/domain/fit.hpp>
#include <mechgraph/domain/tolerance.hpp>
#include <mechgraph/node.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace mechgraph::joints {

/// joint.pin: a pin in one or more bores, each fit's clearance in series.
std::shared_ptr<const NodeType> make_pin_joint_type();
/// joint.spherical: a steel/steel spherical plain bearing (ISO 12240-1), its ring fits, tilt check.
std::shared_ptr<const NodeType> make_spherical_joint_type();
/// joint.cardan: a cardan (Hooke) joint, trunnion clearances and end float, its kinematics.
std::shared_ptr<const NodeType> make_cardan_joint_type();

/// The output ports every joint has, in this order: play, play_min, play_max, play_mean.
inline std::vector<PortSpec> joint_play_ports() {
  return {
      PortSpec::handle("play", std::string(JointPlay::kind_name),
                       "the joint's free-play terms along its line of action (for the stack-up)"),
      PortSpec::scalar("play_min", dim::length, "worst-case least play: sum of max(0, lower limit) over the terms",
                       "um"),
      PortSpec::scalar("play_max", dim::length, "worst-case greatest play: sum of max(0, upper limit) over the terms",
                       "um"),
      PortSpec::scalar("play_mean", dim::length,
                       "sum of max(0, mean) over the terms (each term's untruncated mean clipped at zero)", "um"),
  };
}

/// The optional `label` parameter every joint has: the name of the joint in stack-ups.
inline ParamSpec joint_label_param() {
  return ParamSpec::text("label", "name of this joint in stack-ups and contribution charts (default: a description)")
      .optional();
}

/// The term with every link's sensitivity multiplied by `factor` (a projection or a reduction).
inline PlayTerm scaled(PlayTerm term, double factor) {
  for (ToleranceLink& link : term.links) link.sensitivity *= factor;
  return term;
}

/// The Fit handles connected to `port` (none when the port is absent).
inline std::vector<std::shared_ptr<const Fit>> connected_fits(const InputSet& in, const std::string& port) {
  std::vector<std::shared_ptr<const Fit>> fits;
  for (std::size_t i = 0; i < in.count(port); ++i) fits.push_back(in.handle<Fit>(port, i));
  return fits;
}

/// play_mean as documented above: sum of max(0, mean) over the terms.
inline double clipped_mean(const std::vector<PlayTerm>& terms) {
  double s = 0.0;
  for (const PlayTerm& t : terms) s += std::max(0.0, t.mean());
  return s;
}

/// Sets play, play_min, play_max and play_mean. A term carrying a non-finite number (a broken
/// upstream fit) is reported against `source_port` instead of leaking NaN into the chain.
inline void set_joint_play(OutputSet& out, std::string joint, std::vector<PlayTerm> terms, const std::string& source_port) {
  for (const PlayTerm& t : terms)
    for (const ToleranceLink& l : t.links)
      if (!std::isfinite(l.mean) || !std::isfinite(l.half_range) || !std::isfinite(l.sensitivity))
        throw NodeError(source_port, "play term '" + t.label + "' carries a non-finite value (link '" + l.label + "')");
  const double mean = clipped_mean(terms);
  auto play = std::make_shared<const JointPlay>(std::move(joint), std::move(terms));
  out.set_scalar("play_min", play->play_min());
  out.set_scalar("play_max", play->play_max());
  out.set_scalar("play_mean", mean);
  out.set("play", Value::handle(std::move(play)));
}

}  // namespace mechgraph::joints
