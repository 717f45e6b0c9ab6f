#pragma once
// Calling the spring node types directly and sizing their models.
#include "springs/coil_spring.hpp"
#include "springs/node_types.hpp"
#include "test_support.hpp"

#include <mechgraph/domain/spring.hpp>

#include <map>
#include <string>

namespace mechgraph::springs::testing {

inline const NodeTypeList& all_spring_types() {
  static const NodeTypeList types{make_helical_spring_type(), make_dual_spring_type()};
  return types;
}

/// The model a spring node type makes from its defaults with `given` on top (SI).
inline std::shared_ptr<const SpringModel> spring_model(const NodeType& type, const std::map<std::string, ParamValue>& given = {}) {
  OutputSet out;
  mechgraph::testing::RecordingContext ctx;
  type.evaluate(mechgraph::testing::defaults_of(type.info(), given), InputSet{}, out, ctx);
  return std::dynamic_pointer_cast<const SpringModel>(out.all().at("model").as_handle());
}

inline std::shared_ptr<const SpringModel> spring_model(const std::string& name, const std::map<std::string, ParamValue>& given = {}) {
  for (const auto& t : all_spring_types())
    if (t->info().type == name) return spring_model(*t, given);
  throw std::logic_error(name + " is not a spring type");
}

}  // namespace mechgraph::springs::testing
