// A watched quantity's extremes per segment (extremum_tracker.hpp).
#include "extremum_tracker.hpp"

namespace mechgraph::valvetrain {

void ExtremumTracker::begin(const Sample& start) {
  open_ = true;
  last_ = start;
  current_ = MonitorSegment{start.t, start.t, {start.t, start.value}, {start.t, start.value}};
}

void ExtremumTracker::take(const Sample& s) {
  if (s.value < current_.least.value) current_.least = {s.t, s.value};
  if (s.value > current_.greatest.value) current_.greatest = {s.t, s.value};
}

void ExtremumTracker::extend(const Sample& end, const Probe& q, SearchWork& work) {
  if (!open_) begin(end);
  if (!(end.t > last_.t)) return;
  const Pieces pieces = search_.pieces(last_, end, q, work);
  for (std::size_t i = 0; i + 1 < pieces.size; ++i) {
    const Sample& a = pieces.at[i];
    const Sample& b = pieces.at[i + 1];
    take(b);
    if (monitor_.greatest)
      if (const auto top = search_.interior_max(a, b, current_.greatest.value, q, work)) take(*top);
    if (monitor_.least)
      if (const auto low = search_.interior_min(a, b, current_.least.value, q, work)) take(*low);
  }
  last_ = end;
  current_.end = end.t;
}

void ExtremumTracker::finish(std::vector<MonitorSegment>& segments) {
  if (!open_) return;
  segments.push_back(current_);
  open_ = false;
}

}  // namespace mechgraph::valvetrain
