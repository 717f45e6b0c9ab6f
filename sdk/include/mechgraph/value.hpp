#pragma once
// What flows along the edges of a graph: a scalar, a series over an axis, a table (one axis,
// several named channels), or a handle to a domain object (a cam law, a valve motion, a fit ...). Values are immutable once produced and
// shared between consumers, so evaluation can run on many threads.
#include <mechgraph/dimension.hpp>
#include <mechgraph/export.hpp>

#include <memory>
#include <string>
#include <string_view>
#include <vector>


namespace mechgraph {

/// Base of every domain object passed between nodes. `kind()` names the interface
/// ("cam_law", "valve_motion", ...) and must equal the handle kind of the port carrying it.
class MECHGRAPH_INTERFACE DomainObject {
 public:
  virtual ~DomainObject();  // out of line (key function): one RTTI for host and plugins
  virtual std::string_view kind() const = 0;
  /// Empty when the object keeps its interface's contract, else what it breaks (with the values).
  /// Interfaces implement it `final` in the SDK (CamLaw checks its event, breakpoints and samples),
  /// so an implementation cannot opt out; the host calls it on every domain object a node outputs
  /// and refuses the output with the node type's name and this text.
  virtual std::string contract_problem() const { return {}; }
};

/// Samples of a quantity over an axis (e.g. valve lift over cam angle). Dimensions are those
/// of the ports; `axis_dimension` is carried for writers that print the axis.
struct Series {
  std::vector<double> axis;
  std::vector<double> values;
  Dimension axis_dimension{};
  std::vector<std::string> labels;  // optional: a name per element (a stack's links, a chain's joints)
};

/// A curve with several channels over one axis: SVAJ curves (lift, velocity, acceleration, jerk)
/// over cam angle, or a simulation's state. Every channel has as many values as the axis, its own
/// name and dimension (SI); `display_unit` is how a report prints it ("" = SI).
struct Table {
  struct Column {
    std::string name;
    Dimension dimension{};
    std::vector<double> values;
    std::string display_unit;
  };
  Column axis;
  std::vector<Column> channels;
  /// The channels x, y (and any pair prefix_x, prefix_y) trace closed plane curves in the axis'
  /// order (a cam contour and its pitch curve): writers also give them as DXF polylines.
  bool closed_curve = false;
  /// A histogram: the axis holds the centres of equal bins, each channel the counts in them.
  /// Writers draw bars that touch; the CSV keeps the centres and counts.
  bool histogram = false;
  /// A drawing of a part that turns clockwise seen from the front (data, not a name): a report's
  /// arrow shows it.
  bool turns_clockwise = false;
  /// Reference values on the axis (a specification's limits): plots draw them as vertical lines.
  struct Mark {
    std::string label;
    double value = 0.0;  // SI, of the axis' dimension
  };
  std::vector<Mark> axis_marks;

  /// The channel called `name`, or nullptr.
  const Column* find(std::string_view name) const {
    for (const Column& c : channels)
      if (c.name == name) return &c;
    return nullptr;
  }
  /// Adds a channel; its values are filled by the caller (same length as the axis). The reference
  /// is invalidated by the next add_channel.
  Column& add_channel(std::string name, Dimension d, std::string display_unit = {}) {
    channels.push_back({std::move(name), d, {}, std::move(display_unit)});
    return channels.back();
  }
};

enum class ValueKind { scalar, series, handle, table };

std::string_view to_string(ValueKind kind);

class Value {
 public:
  Value() = default;
  static Value scalar(double v) {
    Value out;
    out.kind_ = ValueKind::scalar;
    out.scalar_ = v;
    return out;
  }
  static Value series(Series s) {
    Value out;
    out.kind_ = ValueKind::series;
    out.series_ = std::make_shared<const Series>(std::move(s));
    return out;
  }
  static Value table(Table t) {
    Value out;
    out.kind_ = ValueKind::table;
    out.table_ = std::make_shared<const Table>(std::move(t));
    return out;
  }
  static Value handle(std::shared_ptr<const DomainObject> object) {
    Value out;
    out.kind_ = ValueKind::handle;
    out.handle_ = std::move(object);
    return out;
  }

  ValueKind kind() const { return kind_; }
  double as_scalar() const { return scalar_; }
  const Series& as_series() const { return *series_; }
  const Table& as_table() const { return *table_; }
  const std::shared_ptr<const DomainObject>& as_handle() const { return handle_; }

 private:
  ValueKind kind_ = ValueKind::scalar;
  double scalar_ = 0.0;
  std::shared_ptr<const Series> series_;
  std::shared_ptr<const Table> table_;
  std::shared_ptr<const DomainObject> handle_;
};

/// Every number a value carries is finite (scalar, series values and axis, table axis and
/// channels; handles carry none). The evaluator refuses an output that is not; the conformance kit
/// checks the same.
bool all_finite(const Value& v);

}  // namespace mechgraph
