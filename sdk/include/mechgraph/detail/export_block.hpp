#pragma once
// Blocks of cases through the SDK 1.x C boundary, the plugin's side (c/node_block.h,
// mechgraph.node.block/1): a C++ NodeType that also implements BlockEvaluation (mechgraph/block.hpp)
// answers the interface, and its block_supported and evaluate_block are called through C.
// Header-only and hidden, compiled into the plugin with export_node.hpp, whose query asks
// BlockExport<NodeTypeExport>::query. Nothing escapes: every exception becomes a status (a block
// that throws is redone case by case by the host, each case giving its own message).
#include <mechgraph/block.hpp>
#include <mechgraph/c/node_block.h>
#include <mechgraph/detail/block_bridge.hpp>
#include <mechgraph/detail/bridge_sets.hpp>
#include <mechgraph/node.hpp>

#include <algorithm>
#include <cstring>
#include <map>
#include <new>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph::detail {

/// What a block sees of the host during its call, over mg_block_host_v1.
class MECHGRAPH_DETAIL_HIDDEN BlockHostContext final : public EvalContext {
 public:
  BlockHostContext(const NodeInfo& info, const mg_block_host_v1& host, mg_block_ctx* ctx) : info_(info), host_(host), ctx_(ctx) {}
  bool effect(std::string_view name) const override {
    for (std::size_t i = 0; i < info_.effects.size(); ++i)
      if (info_.effects[i].name == name) return host_.effect(ctx_, static_cast<std::uint32_t>(i)) != 0;
    return false;
  }
  void log(LogLevel level, std::string_view message) override {
    host_.log(ctx_, level == LogLevel::debug ? MG_LOG_DEBUG : level == LogLevel::info ? MG_LOG_INFO : MG_LOG_WARN,
              {message.data(), message.size()});
  }
  void report_work(std::string_view counter, double amount) override {
    for (std::size_t i = 0; i < info_.work_counters.size(); ++i)
      if (info_.work_counters[i] == counter) return host_.add_work(ctx_, static_cast<std::uint32_t>(i), amount);
    throw std::logic_error("report_work on undeclared counter '" + std::string(counter) + "'");
  }
  bool wanted(std::string_view output) const override {
    for (std::size_t i = 0; i < info_.outputs.size(); ++i)
      if (info_.outputs[i].name == output) return host_.wanted(ctx_, static_cast<std::uint32_t>(i)) != 0;
    return true;
  }

 private:
  const NodeInfo& info_;
  const mg_block_host_v1& host_;
  mg_block_ctx* ctx_;
};

/// mechgraph.node.block/1 over the BlockEvaluation of the C++ type behind an exported node type.
/// `Export` is NodeTypeExport (export_node.hpp): its `type_`.
template <class Export>
struct BlockExport {
  /// The table when `name`/`version` is this interface and the type evaluates blocks, else NULL.
  static const void* query(const NodeType& type, const char* name, std::uint32_t version) noexcept {
    static const mg_node_block_v1 table{sizeof(mg_node_block_v1), &supported, &evaluate_block};
    if (!name || version != 1 || std::strcmp(name, MG_NODE_BLOCK) != 0) return nullptr;
    return dynamic_cast<const BlockEvaluation*>(&type) ? &table : nullptr;
  }

 private:
  static const NodeType& type_of(const mg_node_type* self) { return *static_cast<const Export*>(self->impl)->type_; }
  static ParamSet params_of(const NodeInfo& info, const mg_param_value* params) {
    ParamSet out;
    std::vector<ParamValue*> slots;
    load_params(out, slots, info.params, params);  // bridge_sets.hpp
    return out;
  }

  static mg_status supported(const mg_node_type* self, const mg_block_request* request) noexcept {
    try {
      const NodeType& type = type_of(self);
      const NodeInfo& info = type.info();
      const ParamSet params = params_of(info, request->params);
      std::vector<std::string> wanted, varied;
      for (std::size_t i = 0; i < info.outputs.size(); ++i)
        if (request->wanted[i]) wanted.push_back(info.outputs[i].name);
      std::sort(wanted.begin(), wanted.end());
      for (std::size_t i = 0; i < info.params.size(); ++i)
        if (request->varied[i]) varied.push_back(info.params[i].name);
      return dynamic_cast<const BlockEvaluation&>(type).block_supported(BlockRequest{params, wanted, varied}) ? MG_OK
                                                                                                            : MG_ERR_UNSUPPORTED;
    } catch (const std::bad_alloc&) {
      return MG_ERR_NO_MEMORY;
    } catch (...) {
      return MG_ERR_INTERNAL;
    }
  }

  static mg_status evaluate_block(const mg_node_type* self, const mg_block_args* a) noexcept {
    try {
      const NodeType& type = type_of(self);
      const NodeInfo& info = type.info();
      const std::size_t n = a->size;
      ParamSet fixed = params_of(info, a->params);
      std::map<std::string, BlockColumn, std::less<>> varied;
      for (std::size_t i = 0; i < info.params.size(); ++i)
        if (a->param_columns[i].values) varied.emplace(info.params[i].name, BlockColumn{a->param_columns[i].values, a->param_columns[i].stride});
      const BlockParams params(fixed, std::move(varied));
      BlockInputs inputs;
      for (std::size_t i = 0; i < info.inputs.size(); ++i) {
        const PortSpec& port = info.inputs[i];
        const mg_block_input& in = a->inputs[i];
        if (port.kind == ValueKind::scalar && in.scalar.values) inputs.add_scalar(port.name, {in.scalar.values, in.scalar.stride});
        if (port.kind == ValueKind::handle && in.objects)
          inputs.add_handle(port.name, import_block(*in.objects, port.handle_kind, n, "input block '" + port.name + "'"));
      }
      BlockOutputs outputs(n);
      for (std::size_t i = 0; i < info.outputs.size(); ++i)
        if (a->scalar_outputs[i]) outputs.want_scalar(info.outputs[i].name);
      BlockCases cases(n);
      for (std::size_t k = 0; k < n; ++k)
        if (a->status[k] != MG_OK) cases.fail(k);
      BlockHostContext context(info, *a->host, a->ctx);
      dynamic_cast<const BlockEvaluation&>(type).evaluate_block(params, inputs, outputs, cases, context);
      for (std::size_t i = 0; i < info.outputs.size(); ++i) {
        const PortSpec& port = info.outputs[i];
        if (a->scalar_outputs[i]) {
          const auto it = outputs.scalars().find(port.name);
          std::copy_n(it->second.data(), n, a->scalar_outputs[i]);
        } else if (port.kind == ValueKind::handle && a->host->wanted(a->ctx, static_cast<std::uint32_t>(i))) {
          const auto it = outputs.handles().find(port.name);
          if (it != outputs.handles().end() && it->second) a->object_outputs[i] = export_block(it->second, info.type);
        }
      }
      for (std::size_t k = 0; k < n; ++k)
        if (cases.failed(k) && a->status[k] == MG_OK) a->status[k] = MG_ERR_NODE;
      return MG_OK;
    } catch (const NodeError&) {
      return MG_ERR_NODE;
    } catch (const std::bad_alloc&) {
      return MG_ERR_NO_MEMORY;
    } catch (...) {
      return MG_ERR_INTERNAL;
    }
  }
};

}  // namespace mechgraph::detail
