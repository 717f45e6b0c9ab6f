// The key functions of the interfaces host and plugins share: each class's vtable and RTTI are
// emitted here, in libmechgraph, once, instead of in every plugin (which would export them). One
// RTTI per interface is what makes dynamic_cast of a domain object and catching a NodeError thrown
// in a plugin work whatever the plugin's visibility settings.
#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/domain/fit.hpp>
#include <mechgraph/domain/follower.hpp>
#include <mechgraph/domain/spring.hpp>
#include <mechgraph/domain/tolerance.hpp>
#include <mechgraph/domain/valve_motion.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/node.hpp>
#include <mechgraph/value.hpp>

namespace mechgraph {

DomainObject::~DomainObject() = default;
EvalContext::~EvalContext() = default;
NodeType::~NodeType() = default;
std::optional<WorkForecast> NodeType::forecast(const ParamSet&, const InputSizes&) const { return std::nullopt; }
ForecastReads::~ForecastReads() = default;
CamLaw::~CamLaw() = default;
Fit::~Fit() = default;
Follower::~Follower() = default;
Spring::~Spring() = default;
SpringModel::~SpringModel() = default;
JointPlay::~JointPlay() = default;
ValveMotion::~ValveMotion() = default;
NodeError::~NodeError() = default;
EvaluationError::~EvaluationError() = default;
SceneError::~SceneError() = default;
PluginError::~PluginError() = default;
IoError::~IoError() = default;

}  // namespace mechgraph
