#pragma once
// What flows along the edges of a graph: a scalar, a series over an axis, or a handle to a
// domain object (a cam law, a valve motion, a fit ...). Values are immutable once produced and
// shared between consumers, so evaluation can run on many threads.
#include <mechgraph/dimension.hpp>

#include <memory>
#include <string>
#include <string_view>
#include <vector>

/// Interfaces shared between the host and plugins keep default visibility so that their RTTI
/// (dynamic_cast of domain objects) is one and the same across libraries.
#define MECHGRAPH_INTERFACE __attribute__((visibility("default")))

namespace mechgraph {

/// Base of every domain object passed between nodes. `kind()` names the interface
/// ("cam_law", "valve_motion", ...) and must equal the handle kind of the port carrying it.
class MECHGRAPH_INTERFACE DomainObject {
 public:
  virtual ~DomainObject() = default;
  virtual std::string_view kind() const = 0;
};

/// Samples of a quantity over an axis (e.g. valve lift over cam angle). Dimensions are those
/// of the ports; `axis_dimension` is carried for writers that print the axis.
struct Series {
  std::vector<double> axis;
  std::vector<double> values;
  Dimension axis_dimension{};
};

enum class ValueKind { scalar, series, handle };

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
  static Value handle(std::shared_ptr<const DomainObject> object) {
    Value out;
    out.kind_ = ValueKind::handle;
    out.handle_ = std::move(object);
    return out;
  }

  ValueKind kind() const { return kind_; }
  double as_scalar() const { return scalar_; }
  const Series& as_series() const { return *series_; }
  const std::shared_ptr<const DomainObject>& as_handle() const { return handle_; }

 private:
  ValueKind kind_ = ValueKind::scalar;
  double scalar_ = 0.0;
  std::shared_ptr<const Series> series_;
  std::shared_ptr<const DomainObject> handle_;
};

}  // namespace mechgraph
