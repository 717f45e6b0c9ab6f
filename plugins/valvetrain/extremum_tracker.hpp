#pragma once
// One watched quantity followed step by step: its least and greatest values over each segment
// (a stretch between events inside the monitor's window), the ends of every step counted and the
// turning points inside a step refined on the dense output where they could beat the best so far
// (dense_search.hpp).
#include "dense_search.hpp"
#include "hybrid_simulation.hpp"

#include <vector>

namespace mechgraph::valvetrain {

class ExtremumTracker {
 public:
  ExtremumTracker(const Monitor& monitor, const DenseSearch& search) : monitor_(monitor), search_(search) {}

  bool is_open() const { return open_; }
  /// Opens a segment at `start`.
  void begin(const Sample& start);
  /// Follows the quantity from the last sample to `end` (a later time in the same step).
  void extend(const Sample& end, const Probe& q, SearchWork& work);
  /// Closes the open segment (if any) into `segments`.
  void finish(std::vector<MonitorSegment>& segments);

 private:
  void take(const Sample& s);
  const Monitor& monitor_;
  const DenseSearch& search_;
  bool open_ = false;
  Sample last_;
  MonitorSegment current_;
};

}  // namespace mechgraph::valvetrain
