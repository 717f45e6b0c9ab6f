// The C functions of libmechgraph_sdk.so.1 (sdk/include/mechgraph/c/sdk_lib.h). Nothing escapes
// them: every C++ exception becomes a status.
#include "object_contracts.hpp"

#include <mechgraph/c/sdk_lib.h>
#include <mechgraph/domain/cam_law.hpp>

#include <cmath>
#include <cstring>
#include <new>
#include <string>

namespace {

void put(mg_text_sink sink, const std::string& text) {
  if (sink.append) sink.append(sink.self, text.data(), text.size());
}

// A cam law seen through its C table, so that the contract checks are CamLaw::contract_problem's,
// the same for a C++ law and for one from any plugin.
class CTableCamLaw final : public mechgraph::CamLaw {
 public:
  CTableCamLaw(const mg_object* object, const mg_cam_law_v1* table) : object_(object), table_(table) {
    table_->event(object_, &begin_, &end_);
  }
  double event_begin() const override { return begin_; }
  double event_end() const override { return end_; }
  mechgraph::LiftDerivatives evaluate_in_event(double phi) const override {
    mg_lift4 d{};
    if (table_->evaluate(object_, phi, &d) != MG_OK) {
      const double nan = std::nan("");
      return {nan, nan, nan, nan};  // reported as "a NaN or infinite lift" at that angle
    }
    return {d.h, d.dh, d.d2h, d.d3h};
  }
  std::vector<double> breakpoints() const override {
    // Two calls: the count, then the fill (a law may have many pieces: a table law).
    const std::size_t n = table_->breakpoints(object_, nullptr, 0);
    std::vector<double> out(n);
    if (n > 0) out.resize(std::min(n, table_->breakpoints(object_, out.data(), n)));
    return out;
  }
  double max_lift() const override { return table_->max_lift(object_); }
  double base_radius() const override { return table_->base_radius(object_); }
  double roller_radius() const override { return table_->roller_radius(object_); }

 private:
  const mg_object* object_;
  const mg_cam_law_v1* table_;
  double begin_ = 0.0, end_ = 0.0;
};

bool table_complete(const mg_cam_law_v1* t) {
  return t->struct_size >= sizeof(mg_cam_law_v1) && t->event && t->evaluate && t->evaluate_many && t->breakpoints &&
         t->max_lift && t->base_radius && t->roller_radius;
}

}  // namespace

MG_API void mg_sdk_version(uint16_t* major, uint16_t* minor) {
  if (major) *major = MG_SDK_MAJOR;
  if (minor) *minor = MG_SDK_MINOR;
}

MG_API const char* mg_status_name(mg_status status) {
  switch (status) {
    case MG_OK: return "MG_OK";
    case MG_ERR_NODE: return "MG_ERR_NODE";
    case MG_ERR_CANCELLED: return "MG_ERR_CANCELLED";
    case MG_ERR_NO_MEMORY: return "MG_ERR_NO_MEMORY";
    case MG_ERR_UNSUPPORTED: return "MG_ERR_UNSUPPORTED";
    case MG_ERR_BAD_ARGUMENT: return "MG_ERR_BAD_ARGUMENT";
    case MG_ERR_MISSING_FEATURE: return "MG_ERR_MISSING_FEATURE";
    default: return "MG_ERR_INTERNAL";
  }
}

MG_API mg_status mg_check_object(const mg_object* object, const char* name, uint32_t version, mg_text_sink problem) {
  try {
    if (!object || !object->vtbl || !object->vtbl->query || !name) {
      put(problem, "no object (or one without a vtable)");
      return MG_ERR_BAD_ARGUMENT;
    }
    const void* table = object->vtbl->query(object, name, version);
    if (!table) {
      put(problem, std::string("it does not implement interface '") + name + "' version " + std::to_string(version));
      return MG_ERR_MISSING_FEATURE;
    }
    if (std::strcmp(name, MG_CAM_LAW) == 0 && version == 1) {
      const auto* law = static_cast<const mg_cam_law_v1*>(table);
      if (!table_complete(law)) {
        put(problem, "its mechgraph.cam_law/1 table is incomplete (a function missing or struct_size too small)");
        return MG_ERR_BAD_ARGUMENT;
      }
      const std::string p = CTableCamLaw(object, law).contract_problem();
      if (!p.empty()) {
        put(problem, p);
        return MG_ERR_BAD_ARGUMENT;
      }
      return MG_OK;
    }
    std::string p;
    if (std::strcmp(name, MG_VALVE_MOTION) == 0 && version == 1)
      p = mechgraph::c_checks::valve_motion_problem(object, static_cast<const mg_valve_motion_v1*>(table));
    else if (std::strcmp(name, MG_FOLLOWER) == 0 && version == 1)
      p = mechgraph::c_checks::follower_problem(object, static_cast<const mg_follower_v1*>(table));
    else if (std::strcmp(name, MG_JOINT_PLAY) == 0 && version == 1)
      p = mechgraph::c_checks::joint_play_problem(object, static_cast<const mg_joint_play_v1*>(table));
    if (!p.empty()) {
      put(problem, p);
      return MG_ERR_BAD_ARGUMENT;
    }
    return MG_OK;  // checked, or an interface this library has no checks for (a plugin's private one)
  } catch (const std::bad_alloc&) {
    return MG_ERR_NO_MEMORY;
  } catch (...) {
    return MG_ERR_INTERNAL;
  }
}

MG_API void mg_abi_anchor(const mg_host*, const mg_plugin*, const mg_log_suite_v1*, const mg_eval_suite_v1*,
                          const mg_memory_suite_v1*, const mg_node_type*, const mg_eval_args*, const mg_error*,
                          const mg_series*, const mg_table*, const mg_value*, const mg_object*, const mg_cam_law_v1*,
                          const mg_cam_law_closed_form_v1*, const mg_cam_law_higher_v1*, const mg_valve_motion_v1*,
                          const mg_joint_play_v1*, const mg_follower_v1*, const mg_owner*) {}

MG_API void mg_abi_anchor_1_1(const mg_node_forecast_v1*, const mg_work_forecast*, const mg_fit_v1*, const mg_spring_model_v1*,
                              const mg_spring_v1*) {}

MG_API void mg_abi_anchor_1_2(const mg_node_block_v1*, const mg_block_args*, const mg_block_request*, const mg_block_host_v1*,
                              const mg_object_block*, const mg_block_input*, const mg_block_column*) {}

MG_API void mg_abi_anchor_1_3(const mg_node_forecast_reads_v1*) {}

MG_API void mg_abi_anchor_1_4(const mg_object_cxx_v1*) {}

MG_API void mg_abi_anchor_1_5(const mg_node_cxx_v1*) {}
