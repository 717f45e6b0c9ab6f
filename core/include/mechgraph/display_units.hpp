#pragma once
// The units a scene asks results to be shown in (`units: { length: mm, angle: deg }`): files and
// text a person reads (CSV columns, printed outputs, reports) use them; JSON stays SI. A quantity
// named in `units:` is used for exactly its dimension; a dimension made only of base quantities the
// scene names is composed from them (length: mm and angle: deg show an acceleration over an angle in
// mm/deg^2); anything else stays SI.
#include <mechgraph/dimension.hpp>
#include <mechgraph/scene.hpp>
#include <mechgraph/units.hpp>

#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mechgraph {

class DisplayUnits {
 public:
  DisplayUnits() = default;
  /// Reads a scene's `units:`; throws SceneError at the key or value that is wrong (an unknown
  /// quantity with the valid names, a unit that does not parse or is of another dimension).
  static DisplayUnits from_scene(const std::vector<std::pair<std::string, RawValue>>& units);

  /// The unit to show a value of dimension `d` in; "" means SI.
  std::string unit_for(Dimension d) const;
  /// `unit_for(d)`, or `fallback` when that is SI (a column's own display unit, a report row's).
  std::string unit_for(Dimension d, const std::string& fallback) const;
  bool empty() const { return named_.empty(); }

  /// The quantity names `units:` accepts, with their dimensions.
  static const std::vector<std::pair<std::string, Dimension>>& quantities();

 private:
  std::vector<std::pair<Dimension, std::string>> named_;  // dimension -> unit, as written
};

/// `unit` followed by the angle reference, "deg (shaft)", when the unit counts degrees and there is
/// a reference; `unit` as it is otherwise (SI radians carry no tag). The one rule of every label a
/// host writes (host/angle_reference.hpp says where the reference comes from).
std::string unit_with_reference(const std::string& unit, const std::string& reference);
/// The unit of a label's "deg (shaft)" without its reference ("deg"); `unit` as it is when it
/// carries none. The reference says which angle is counted, never a scale: a label's unit reads
/// back through this (a cases file's header, Python's unit_scale).
std::string unit_without_reference(const std::string& unit);

/// parse_unit(unit), parsed once per thread and kept (a sweep shows the same few units in every
/// case); nullopt for a unit that does not parse. The reference lives as long as the thread.
const std::optional<UnitScale>& parse_unit_cached(std::string_view unit);

/// Whether SI values up to `magnitude` either side of 0 stay finite shown in `u` (x / scale -
/// offset): 1e300 m does not in nm. What a run refuses to show, and the block path with it.
inline bool finite_in_unit(double magnitude, const UnitScale& u) {
  return std::isfinite(magnitude / u.scale - u.offset) && std::isfinite(-magnitude / u.scale - u.offset);
}

}  // namespace mechgraph
