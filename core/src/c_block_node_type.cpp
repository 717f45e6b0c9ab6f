#include "c_block_node_type.hpp"

#include <mechgraph/block.hpp>
#include <mechgraph/c/node_block.h>
#include <mechgraph/c/sdk_lib.h>
#include <mechgraph/cancellation.hpp>
#include <mechgraph/detail/block_bridge.hpp>

#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

// The per-call state behind the opaque mg_block_ctx of node_block.h.
struct mg_block_ctx {
  const mechgraph::NodeInfo& info;
  mechgraph::EvalContext& context;
  std::string defect;  // a broken contract of the boundary (a counter index out of range ...)
};

namespace mechgraph::detail {
namespace {

// --- mg_block_host_v1: the host's side of a block call; nothing escapes into the plugin --------
int32_t block_effect(mg_block_ctx* c, uint32_t index) {
  try {
    return index < c->info.effects.size() && c->context.effect(c->info.effects[index].name) ? 1 : 0;
  } catch (...) {
    return 0;
  }
}
int32_t block_wanted(mg_block_ctx* c, uint32_t index) {
  try {
    return index < c->info.outputs.size() && c->context.wanted(c->info.outputs[index].name) ? 1 : 0;
  } catch (...) {
    return 1;
  }
}
int32_t block_cancelled(mg_block_ctx*) { return cancellation_requested() ? 1 : 0; }
void block_log(mg_block_ctx* c, int32_t level, mg_str message) {
  try {
    c->context.log(level <= MG_LOG_DEBUG ? LogLevel::debug : level == MG_LOG_INFO ? LogLevel::info : LogLevel::warn,
                   message.data ? std::string_view(message.data, message.size) : std::string_view());
  } catch (...) {
  }
}
void block_add_work(mg_block_ctx* c, uint32_t index, double amount) {
  try {
    if (index >= c->info.work_counters.size()) {
      if (c->defect.empty())
        c->defect = "add_work was given counter index " + std::to_string(index) + " of " + std::to_string(c->info.work_counters.size()) +
                    " declared work counters";
      return;
    }
    c->context.report_work(c->info.work_counters[index], amount);
  } catch (const std::exception& e) {
    if (c->defect.empty()) c->defect = e.what();
  } catch (...) {
  }
}
const mg_block_host_v1 block_host{sizeof(mg_block_host_v1), &block_effect, &block_wanted, &block_cancelled, &block_log,
                                  &block_add_work};

// The C views of a block's fixed parameters, over the ParamSet's storage (declaration order; an
// absent optional one is `present` 0, as evaluate receives it).
class ParamViews {
 public:
  ParamViews(const NodeInfo& info, const ParamSet& params) {
    values_.reserve(info.params.size());
    for (const ParamSpec& spec : info.params) values_.push_back(params.has(spec.name) ? view(params.get(spec.name), spec) : absent(spec));
  }
  const mg_param_value* data() const { return values_.data(); }

 private:
  static mg_param_value absent(const ParamSpec& spec) {
    mg_param_value out{};
    out.kind = static_cast<int32_t>(spec.kind) + 1;  // ParamKind's order is MG_PARAM_*'s, from 1
    return out;
  }
  mg_param_value view(const ParamValue& v, const ParamSpec& spec) {
    mg_param_value out = absent(spec);
    out.present = 1;
    out.number = v.number;
    out.text = {v.text.data(), v.text.size()};
    out.numbers = v.numbers.data();
    out.number_count = v.numbers.size();
    if (spec.kind == ParamKind::record_list) {
      auto& records = *records_.emplace_back(std::make_unique<std::vector<mg_record>>());
      for (const Record& r : v.records) {
        auto& fields = *fields_.emplace_back(std::make_unique<std::vector<mg_param_value>>());
        for (const ParamSpec& f : spec.fields) {
          const auto it = r.find(f.name);
          fields.push_back(it != r.end() ? view(it->second, f) : absent(f));
        }
        records.push_back({fields.data(), fields.size()});
      }
      out.records = records.data();
      out.record_count = records.size();
    }
    return out;
  }
  std::vector<mg_param_value> values_;
  std::vector<std::unique_ptr<std::vector<mg_record>>> records_;
  std::vector<std::unique_ptr<std::vector<mg_param_value>>> fields_;
};

// An output block of a C node as the host keeps it: the C++ view that sweeps and pre-1.0 consumers
// read, and the C block as it came (its owner released once, when the last holder lets go),
// which C consumers get as it is, so that its producer may find its own block again.
struct AdoptedBlock {
  AdoptedBlock(const mg_object_block& c, BlockOwner&& o, std::shared_ptr<const DomainBlock> v)
      : block(c), owner(std::move(o)), view(std::move(v)) {}
  mg_object_block block;  // its owner is for its producer to recognise; `owner` releases it
  BlockOwner owner;
  std::shared_ptr<const DomainBlock> view;
};
// The deleter of the view handed to sweeps: it keeps the AdoptedBlock, and finds it again
// (std::get_deleter) when the view is an input of another C node.
struct KeepAdopted {
  std::shared_ptr<const AdoptedBlock> adopted;
  void operator()(const DomainBlock*) const {}
};

template <class Container>
std::size_t index_of(const Container& items, std::string_view name) {
  for (std::size_t i = 0; i < items.size(); ++i)
    if (items[i].name == name) return i;
  return SIZE_MAX;
}

// A C node type with blocks: the host's wrapper of the type for everything else, its
// mechgraph.node.block/1 table for blocks.
class CBlockNodeType final : public NodeType, public BlockEvaluation, public ForecastReads {
 public:
  CBlockNodeType(std::shared_ptr<const NodeType> type, const mg_node_type& c_type, const mg_node_block_v1& blocks)
      : type_(std::move(type)), c_type_(c_type), blocks_(blocks) {}
  const NodeType& c_node_type() const { return *type_; }

  const NodeInfo& info() const override { return type_->info(); }
  void evaluate(const ParamSet& params, const InputSet& inputs, OutputSet& outputs, EvalContext& context) const override {
    type_->evaluate(params, inputs, outputs, context);
  }
  std::optional<WorkForecast> forecast(const ParamSet& params, const InputSizes& sizes) const override {
    return type_->forecast(params, sizes);
  }
  std::optional<std::vector<std::string>> forecast_reads() const override {
    const auto* reads = dynamic_cast<const ForecastReads*>(type_.get());
    return reads ? reads->forecast_reads() : std::nullopt;
  }

  bool block_supported(const BlockRequest& request) const override {
    const NodeInfo& info = type_->info();
    const ParamViews params(info, request.params);
    std::vector<int32_t> wanted(info.outputs.size(), 0), varied(info.params.size(), 0);
    for (std::size_t i = 0; i < info.outputs.size(); ++i) wanted[i] = request.wants(info.outputs[i].name) ? 1 : 0;
    for (const std::string& name : request.varied)
      if (const std::size_t i = index_of(info.params, name); i != SIZE_MAX) varied[i] = 1;
    const mg_block_request c{sizeof(mg_block_request), params.data(), wanted.data(), varied.data()};
    return blocks_.supported(&c_type_, &c) == MG_OK;
  }

  // Throws (the host then redoes the block case by case) when the call fails as a whole or breaks
  // the boundary's contract.
  void evaluate_block(const BlockParams& params, const BlockInputs& inputs, BlockOutputs& outputs, BlockCases& cases,
                      EvalContext& context) const override {
    const NodeInfo& info = type_->info();
    const std::size_t n = cases.size();
    const ParamViews fixed(info, params.fixed());
    std::vector<mg_block_column> columns(info.params.size(), mg_block_column{nullptr, 0});
    for (std::size_t i = 0; i < info.params.size(); ++i)
      if (params.varies(info.params[i].name)) {
        const BlockColumn c = params.number(info.params[i].name);
        columns[i] = {c.data, c.stride};
      }
    // Inputs: scalar columns as they are; a block a C node made as it came, another exported for
    // the call (released after it). The laws passed in are known when they come back out.
    std::vector<mg_block_input> c_inputs(info.inputs.size(), mg_block_input{{nullptr, 0}, nullptr});
    std::vector<mg_object_block> input_blocks(info.inputs.size());
    std::vector<BlockOwner> input_owners;
    input_owners.reserve(info.inputs.size());
    KnownLaws known;
    for (std::size_t i = 0; i < info.inputs.size(); ++i) {
      const PortSpec& port = info.inputs[i];
      try {
        if (port.kind == ValueKind::scalar) {
          const BlockColumn c = inputs.scalar(port.name);
          c_inputs[i].scalar = {c.data, c.stride};
        } else if (port.kind == ValueKind::handle) {
          const std::shared_ptr<const DomainBlock> block = inputs.shared_handle<DomainBlock>(port.name);
          if (const KeepAdopted* adopted = std::get_deleter<KeepAdopted>(block)) {
            input_blocks[i] = adopted->adopted->block;
          } else {
            input_blocks[i] = export_block(block, "");
            input_owners.emplace_back(input_blocks[i].owner);
          }
          c_inputs[i].objects = &input_blocks[i];
          if (!known.objects) known = {input_blocks[i].objects, input_blocks[i].object_count, block.get()};
        }
      } catch (const NodeError&) {
        // not connected: {NULL, 0} and NULL
      }
    }
    std::vector<double*> scalar_outputs(info.outputs.size(), nullptr);
    for (std::size_t i = 0; i < info.outputs.size(); ++i)
      if (info.outputs[i].kind == ValueKind::scalar) scalar_outputs[i] = outputs.scalar(info.outputs[i].name);
    std::vector<mg_object_block> object_outputs(info.outputs.size(), mg_object_block{});
    std::vector<int32_t> status(n, MG_OK);
    for (std::size_t k = 0; k < n; ++k)
      if (cases.failed(k)) status[k] = MG_ERR_NODE;
    mg_block_ctx call{info, context, {}};
    const mg_block_args args{sizeof(mg_block_args), n,   fixed.data(),          columns.data(), c_inputs.data(),
                             scalar_outputs.data(),  object_outputs.data(), status.data(), &block_host, &call};
    const mg_status result = blocks_.evaluate_block(&c_type_, &args);
    // Whatever the status, what was handed over is released once: with its C++ view when it is
    // adopted, here when not.
    std::vector<BlockOwner> output_owners;
    output_owners.reserve(info.outputs.size());
    for (const mg_object_block& b : object_outputs) output_owners.emplace_back(b.owner);
    if (!call.defect.empty()) throw std::runtime_error("broke the C boundary's contract: " + call.defect + " (a defect of its plugin)");
    if (result != MG_OK) throw std::runtime_error(std::string("a block returned ") + mg_status_name(result));
    for (std::size_t i = 0; i < info.outputs.size(); ++i) {
      const PortSpec& port = info.outputs[i];
      if (port.kind != ValueKind::handle || object_outputs[i].struct_size == 0) continue;
      std::shared_ptr<const DomainBlock> view =
          import_block(object_outputs[i], port.handle_kind, n, "output block '" + port.name + "'", known);
      const auto adopted = std::make_shared<const AdoptedBlock>(object_outputs[i], std::move(output_owners[i]), std::move(view));
      outputs.set_handle(port.name, std::shared_ptr<const DomainBlock>(adopted->view.get(), KeepAdopted{adopted}));
    }
    for (std::size_t k = 0; k < n; ++k)
      if (status[k] != MG_OK) cases.fail(k);
  }

 private:
  std::shared_ptr<const NodeType> type_;
  const mg_node_type& c_type_;
  const mg_node_block_v1& blocks_;
};

// The type's mechgraph.node.block/1 table, or nullptr (as node_forecast in c_node_type.cpp: a
// short mg_node_type, a NULL query or answer, or a function missing counts as none).
const mg_node_block_v1* node_block(const mg_node_type& type) {
  if (!MG_HAS_FIELD(&type, mg_node_type, query) || !type.query) return nullptr;
  const auto* table = static_cast<const mg_node_block_v1*>(type.query(&type, MG_NODE_BLOCK, 1));
  return table && MG_HAS_FIELD(table, mg_node_block_v1, evaluate_block) && table->supported && table->evaluate_block ? table : nullptr;
}

}  // namespace

std::shared_ptr<const NodeType> with_c_blocks(std::shared_ptr<const NodeType> type, const mg_node_type& c_type) {
  const mg_node_block_v1* blocks = node_block(c_type);
  if (!blocks) return type;
  return std::make_shared<const CBlockNodeType>(std::move(type), c_type, *blocks);
}

const NodeType* c_type_behind_blocks(const NodeType& type) {
  const auto* blocks = dynamic_cast<const CBlockNodeType*>(&type);
  return blocks ? &blocks->c_node_type() : nullptr;
}

}  // namespace mechgraph::detail
