#pragma once
// A node type of an SDK 1.x plugin (mg_node_type, sdk/include/mechgraph/c/node.h) behind the
// host's one node interface, NodeType: the evaluator, sweeps, the conformance kit and every writer
// use it like any other type. Its description is converted once (c_node_description.hpp); each
// evaluation passes the parameters and inputs as C views (no copies of arrays) and collects the
// outputs through the eval suite. Private to libmechgraph.
#include <mechgraph/c/host.h>
#include <mechgraph/c/node.h>
#include <mechgraph/node.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mechgraph::detail {

/// The eval suite v1 the host gives C plugins (mechgraph.eval/1).
const mg_eval_suite_v1& c_eval_suite();

/// The C interface an object port carries: an SDK interface's name for the kind of its C++ class
/// ("mechgraph.KIND" for an SDK kind KIND), else the port's kind, which is then the interface name itself
/// (a plugin's private one).
std::string interface_of_port(const PortSpec& port);

/// Wraps `type` (checked: PluginError naming `where` and the field on a malformed description).
/// Unless `through_c`, a type whose C++ layer is the host's (mechgraph.node.cxx/1, equal keys)
/// is taken as itself: the plugin's C++ NodeType, called as the host's own types are.
std::shared_ptr<const NodeType> make_c_node_type(const mg_node_type& type, const std::string& where, bool through_c);

/// Whether `type` is the host's view of an SDK 1.x type's C description and evaluate function
/// (make_c_node_type's wrapper), as opposed to a C++ type called as itself.
bool runs_through_c(const NodeType& type);

/// The C++ type behind `type` when its library's C++ layer is the host's (mechgraph.node.cxx/1,
/// equal keys) and its declaration reads from C as it is: its ports carry only the SDK's
/// interfaces (a private one is named after its plugin, which only the C description does), no
/// required parameter has a default, no table port a dimension. Else nullptr.
std::shared_ptr<const NodeType> same_cxx_node_type(const mg_node_type& type);

/// The interface versions of a node type's object ports, by port index (RegisteredType): an SDK
/// 1.x type's declared ones; for any other type the version of the SDK interface its port's C++
/// class is bridged as (object_bridge.hpp), 0 for a private kind or a port that is no object.
struct PortInterfaceVersions {
  std::vector<std::uint32_t> inputs, outputs;
};
PortInterfaceVersions port_interface_versions(const NodeType& type);

/// An SDK 1.x type's own forecast (mechgraph.node.forecast/1) bound to one ParamSet, for a caller
/// that asks it again and again while only the values change (a sweep's budget, case after case:
/// RepeatedNodeEstimate). The set's entries are matched with the declaration once, here; each call
/// then reads the values through the matched entries. The set must outlive the binding and keep
/// its entries (values written in place, as CaseBinder::apply writes them; none added or removed).
class BoundForecast {
 public:
  virtual ~BoundForecast() = default;
  /// What NodeType::forecast(params, sizes) gives for the bound set as it is now, less the
  /// driver's text (left empty: the figures of case after case never name it; estimate_node asks
  /// NodeType::forecast when they must). Not for concurrent calls (each worker binds its own).
  virtual std::optional<WorkForecast> operator()(const InputSizes& sizes) = 0;
};
/// nullptr when `type` is not an SDK 1.x type that offers a forecast of its own (the caller then
/// asks NodeType::forecast).
std::unique_ptr<BoundForecast> bind_forecast(const NodeType& type, const ParamSet& params);

/// Whether an SDK 1.x type's table offers a forecast (mechgraph.node.forecast/1 with its function).
bool c_type_offers_forecast(const mg_node_type& type);

/// The parameters `type`'s forecast reads, when it says (mechgraph.node.forecast_reads/1 for an
/// SDK 1.x type, ForecastReads for a C++ one) and every name is one of its parameters; none
/// otherwise (the forecast may read any parameter).
std::optional<std::vector<std::string>> forecast_reads(const NodeType& type);

}  // namespace mechgraph::detail
