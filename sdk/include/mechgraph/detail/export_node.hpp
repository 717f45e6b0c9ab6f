#pragma once
// C++ node types exported through the SDK 1.x C boundary (docs/design/sdk-1.0.md, section 3):
// header-only, compiled into the plugin with hidden visibility, so no C++ type, exception or
// allocator crosses to the host. Each NodeType's NodeInfo becomes an mg_node_desc once, at the
// entry; each evaluation refreshes the ParamSet, InputSet and OutputSet this node type keeps on
// this thread from the C arguments (mechgraph/detail/bridge_sets.hpp: no allocation once they have
// their shape), runs the node, and hands its outputs to the host through the eval suite by index. Every exception is caught
// here (OpenFX's ladder): NodeError -> fail() + MG_ERR_NODE, std::bad_alloc -> MG_ERR_NO_MEMORY,
// anything else -> fail() + MG_ERR_INTERNAL.
//
// Domain objects cross through mechgraph/detail/object_bridge.hpp: a port whose kind is an SDK
// interface's C++ class (CamLaw, ValveMotion) declares that interface ("mechgraph.cam_law"/1);
// any other kind becomes the plugin's private interface "<plugin id>.<kind>", which only this
// plugin's own nodes can read. Until the C++ helpers leave libmechgraph_sdk (migration step 6) the plugin still calls them, so it
// must share the host's C++ standard library ABI (libstdc++; any compiler).
#include <mechgraph/c/node.h>
#include <mechgraph/c/node_cxx.h>
#include <mechgraph/c/node_forecast.h>
#include <mechgraph/c/node_forecast_reads.h>
#include <mechgraph/c/plugin.h>
#include <mechgraph/detail/bridge_sets.hpp>
#include <mechgraph/detail/export_block.hpp>
#include <mechgraph/detail/forecast_override.hpp>
#include <mechgraph/detail/object_bridge.hpp>
#include <mechgraph/node.hpp>
#include <mechgraph/version.hpp>

#include <algorithm>
#include <utility>
#include <atomic>
#include <cstring>
#include <deque>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph::detail {

/// The host's suites, fetched once at the entry.
struct HostSuites {
  const mg_eval_suite_v1* eval = nullptr;
};
inline HostSuites& host_suites() {
  static HostSuites suites;
  return suites;
}

inline mg_str c_text(std::string_view s) { return {s.data(), s.size()}; }
inline mg_dim c_dim(const Dimension& d) { return {d.length, d.mass, d.time, d.angle, d.temperature, 0, 0, 0}; }

// A node asks by name for each output it may skip (wanted) and each effect: the length and the
// first character rule out most declared names before their characters are compared.
template <class Container>
std::uint32_t index_of(const Container& items, std::string_view name) {
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string& item = items[i].name;
    if (item.size() == name.size() && (name.empty() || item[0] == name[0]) && item == name) return static_cast<std::uint32_t>(i);
  }
  return UINT32_MAX;
}

/// A type's declared outputs, for the questions a node asks by name during an evaluation: each
/// name's length and first and last characters packed in one word, in declaration order, so a
/// look-up compares words and only the one name whose word matches.
struct OutputIndex {
  std::vector<std::string_view> names;
  std::vector<std::uint32_t> keys;
  static std::uint32_t key(std::string_view name) {
    if (name.empty()) return 0;
    return static_cast<std::uint32_t>(name.size() & 0xffffu) << 16 | static_cast<std::uint32_t>(static_cast<unsigned char>(name.front())) << 8 |
           static_cast<unsigned char>(name.back());
  }
};
inline OutputIndex output_index(const NodeInfo& info) {
  OutputIndex index;
  for (const PortSpec& p : info.outputs) {
    index.names.push_back(p.name);
    index.keys.push_back(OutputIndex::key(p.name));
  }
  return index;
}
/// The declared index of output `name`, or UINT32_MAX.
inline std::uint32_t find_output(const OutputIndex& index, std::string_view name) {
  const std::uint32_t k = OutputIndex::key(name);
  for (std::size_t i = 0; i < index.keys.size(); ++i)
    if (index.keys[i] == k && index.names[i] == name) return static_cast<std::uint32_t>(i);
  return UINT32_MAX;
}

/// What a node sees of the host during one evaluation, over the eval suite.
class SuiteContext final : public EvalContext {
 public:
  // `wanted`: the host's flags by declared output (mg_eval_args::wanted, SDK 1.4), or nullptr for
  // a host that gives none (then each question goes through the suite).
  SuiteContext(const NodeInfo& info, const OutputIndex& outputs, mg_eval_ctx* ctx, const std::int32_t* wanted)
      : info_(info), outputs_(outputs), ctx_(ctx), wanted_(wanted) {}
  bool effect(std::string_view name) const override {
    const std::uint32_t i = index_of(info_.effects, name);
    return i != UINT32_MAX && host_suites().eval->effect(ctx_, i) != 0;
  }
  void log(LogLevel level, std::string_view message) override {
    host_suites().eval->log(ctx_, level == LogLevel::debug ? MG_LOG_DEBUG : level == LogLevel::info ? MG_LOG_INFO : MG_LOG_WARN,
                            c_text(message));
  }
  void report_work(std::string_view counter, double amount) override {
    for (std::size_t i = 0; i < info_.work_counters.size(); ++i)
      if (info_.work_counters[i] == counter) return host_suites().eval->add_work(ctx_, static_cast<std::uint32_t>(i), amount);
    throw std::logic_error("report_work on undeclared counter '" + std::string(counter) + "'");
  }
  bool wanted(std::string_view output) const override {
    const std::uint32_t i = find_output(outputs_, output);
    if (i == UINT32_MAX) return true;
    return wanted_ ? wanted_[i] != 0 : host_suites().eval->wanted(ctx_, i) != 0;
  }

 private:
  const NodeInfo& info_;
  const OutputIndex& outputs_;
  mg_eval_ctx* ctx_;
  const std::int32_t* wanted_;
};

inline void tell(mg_text_sink why, std::string_view text) {
  if (why.append) why.append(why.self, text.data(), text.size());
}

// Each thread's BridgeSets, by NodeTypeExport::sets_index_; this plugin's own (hidden), made when
// a thread first evaluates a type, kept until the thread ends (they hold no object between calls).
MECHGRAPH_DETAIL_HIDDEN inline std::vector<std::unique_ptr<BridgeSets>>& thread_bridge_sets() {
  thread_local std::vector<std::unique_ptr<BridgeSets>> sets;
  return sets;
}
MECHGRAPH_DETAIL_HIDDEN inline std::size_t next_bridge_sets_index() {
  static std::atomic<std::size_t> next{0};
  return next++;
}

/// One C++ NodeType and the C description that stands for it; lives until the process ends.
class NodeTypeExport {
 public:
  NodeTypeExport(std::shared_ptr<const NodeType> type, std::string_view plugin_id)
      : type_(std::move(type)),
        sets_index_(next_bridge_sets_index()),
        has_forecast_(has_own_forecast(*type_)),
        output_index_(output_index(type_->info())) {
    const NodeInfo& info = type_->info();
    // Presentation (c/present.h): frames and channels name a frame by its index in `frames`.
    for (const AngleFrame& f : info.frames) {
      const auto& labels = names(f.mark_labels);
      frames_.push_back(mg_angle_frame{sizeof(mg_angle_frame), f.id.c_str(), f.label.c_str(), f.unit_tag.c_str(),
                                       f.zero.c_str(), frame_index(f.base_frame), f.scale, optional_text(f.offset_param),
                                       f.mark_spacing, labels.data(), labels.size(), f.before.c_str(), f.after.c_str()});
    }
    for (const NoteDecl& n : info.notes)
      notes_.push_back(mg_note_decl{sizeof(mg_note_decl), n.output.c_str(), optional_text(n.when_param), n.doc.c_str()});
    for (const ParamSpec& p : info.params) params_.push_back(param_decl(p));
    for (const PortSpec& p : info.inputs) inputs_.push_back(port_decl(p, plugin_id, input_interfaces_));
    for (const PortSpec& p : info.outputs) outputs_.push_back(port_decl(p, plugin_id, output_interfaces_));
    for (const EffectSpec& e : info.effects) {
      const auto& outs = names(e.outputs);
      const auto& ps = names(e.params);
      effects_.push_back({sizeof(mg_effect_decl), e.name.c_str(), e.doc.c_str(), outs.data(), outs.size(), ps.data(), ps.size()});
    }
    for (const std::string& c : info.work_counters) counters_.push_back({sizeof(mg_counter_decl), c.c_str(), ""});
    for (const auto& [output, ins] : info.output_dependencies) {
      const auto& list = names(ins);
      deps_.push_back({output.c_str(), list.data(), list.size()});
    }
    desc_ = mg_node_desc{sizeof(mg_node_desc), info.type.c_str(), info.version, info.summary.c_str(),
                         params_.data(), params_.size(), inputs_.data(), inputs_.size(), outputs_.data(), outputs_.size(),
                         effects_.data(), effects_.size(), counters_.data(), counters_.size(), deps_.data(), deps_.size(),
                         frames_.data(), frames_.size(), notes_.data(), notes_.size()};
    c_type_ = mg_node_type{sizeof(mg_node_type), &desc_, this, &NodeTypeExport::evaluate, &NodeTypeExport::query};
    // mechgraph.node.forecast_reads/1: the declared parameters' indices. A forecast_reads() that
    // throws, or names no declared parameter, withholds the table: the type loads and its forecast
    // is asked case by case, as the host treats a C++ type's (the conformance kit, run on the C++
    // type in the plugin's own tests, names the fault).
    std::optional<std::vector<std::string>> names;
    try {
      const auto* reads = dynamic_cast<const ForecastReads*>(type_.get());
      if (reads && has_forecast_) names = reads->forecast_reads();
    } catch (...) {
    }
    if (names) {
      has_reads_ = true;
      for (const std::string& name : *names) {
        const ParamSpec* spec = info.find_param(name);
        if (!spec) has_reads_ = false;
        else forecast_reads_.push_back(static_cast<std::uint32_t>(spec - info.params.data()));
      }
      reads_table_ = mg_node_forecast_reads_v1{sizeof(mg_node_forecast_reads_v1), forecast_reads_.data(), forecast_reads_.size()};
    }
  }
  NodeTypeExport(const NodeTypeExport&) = delete;
  NodeTypeExport& operator=(const NodeTypeExport&) = delete;
  const mg_node_type* c_type() const { return &c_type_; }

 private:
  template <class>
  friend struct BlockExport;  // blocks of cases (export_block.hpp): type_
  const std::vector<const char*>& names(const std::vector<std::string>& list) {
    auto& out = lists_.emplace_back();
    for (const std::string& s : list) out.push_back(s.c_str());
    return out;
  }
  static std::int32_t c_param_kind(ParamKind k) { return static_cast<std::int32_t>(k) + 1; }  // MG_PARAM_* order
  static const char* optional_text(const std::string& s) { return s.empty() ? nullptr : s.c_str(); }

  // Frame `id` as C names it, MG_FRAME(its index in NodeInfo::frames), MG_NO_FRAME for none; an id
  // the type does not declare refuses the plugin at its entry (the conformance kit names it in the
  // plugin's own tests).
  std::int32_t frame_index(const std::string& id) const {
    if (id.empty()) return MG_NO_FRAME;
    const auto& frames = type_->info().frames;
    for (std::size_t i = 0; i < frames.size(); ++i)
      if (frames[i].id == id) return MG_FRAME(i);
    throw std::invalid_argument("node type '" + type_->info().type + "' names angle frame '" + id + "', which it does not declare");
  }
  mg_channel_decl channel_decl(const ChannelDecl& c) {
    mg_channel_decl d{};
    d.struct_size = sizeof d;
    d.name = c.name.c_str();
    d.dim = c_dim(c.dimension);
    d.label = optional_text(c.label);
    d.display_unit = optional_text(c.display_unit);
    d.angle_frame = frame_index(c.angle_frame);
    d.derivative_order = c.derivative_order;
    d.flags = c.flags;
    auto& codes = codes_.emplace_back();
    for (const Code& k : c.codes) codes.push_back({k.value, k.name.c_str(), k.doc.c_str()});
    d.codes = codes.data();
    d.code_count = codes.size();
    d.from_mark = optional_text(c.from_mark);
    return d;
  }
  const mg_presentation* presentation(const Presentation& p) {
    if (p.empty()) return nullptr;
    mg_presentation& d = presentations_.emplace_back();
    d.struct_size = sizeof d;
    d.role = static_cast<std::int32_t>(p.role);
    if (p.has_axis) d.axis = &axes_.emplace_back(channel_decl(p.axis));
    auto& channels = channel_lists_.emplace_back();
    for (const ChannelDecl& c : p.channels) channels.push_back(channel_decl(c));
    d.channels = channels.data();
    d.channel_count = channels.size();
    d.x_channel = optional_text(p.x_channel);
    auto& pairs = pairs_.emplace_back();
    for (const XyPair& xy : p.pairs) pairs.push_back({xy.x.c_str(), xy.y.c_str(), xy.layer.c_str(), optional_text(xy.label), xy.stroke});
    d.pairs = pairs.data();
    d.pair_count = pairs.size();
    auto& points = points_.emplace_back();
    for (const PointMarks& m : p.points) {
      if (m.labels.size() != m.x_channels.size())
        throw std::invalid_argument("node type '" + type_->info().type + "': points from '" + m.port + "' have " +
                                    std::to_string(m.x_channels.size()) + " x channels but " + std::to_string(m.labels.size()) + " labels");
      const auto& xs = names(m.x_channels);
      const auto& labels = names(m.labels);
      points.push_back({m.port.c_str(), m.row, xs.data(), labels.data(), xs.size(), m.y_from_axis ? 1 : 0, optional_text(m.caption)});
    }
    d.points = points.data();
    d.point_count = points.size();
    d.figure_title = optional_text(p.figure_title);
    d.caption = optional_text(p.caption);
    return &d;
  }

  mg_param_value c_value(const ParamValue& v, const ParamSpec& spec) {
    mg_param_value out{};
    out.kind = c_param_kind(spec.kind);
    out.present = 1;
    out.number = v.number;
    out.text = c_text(v.text);
    out.numbers = v.numbers.data();
    out.number_count = v.numbers.size();
    if (spec.kind == ParamKind::record_list) {
      auto& records = records_.emplace_back();
      for (const Record& r : v.records) {
        auto& fields = values_.emplace_back();
        for (const ParamSpec& f : spec.fields) {
          const auto it = r.find(f.name);
          mg_param_value absent{};
          absent.kind = c_param_kind(f.kind);
          fields.push_back(it != r.end() ? c_value(it->second, f) : absent);
        }
        records.push_back({fields.data(), fields.size()});
      }
      out.records = records.data();
      out.record_count = records.size();
    }
    return out;
  }
  mg_param_decl param_decl(const ParamSpec& p) {
    mg_param_decl d{};
    d.struct_size = sizeof d;
    d.name = p.name.c_str();
    d.kind = c_param_kind(p.kind);
    d.dim = c_dim(p.dimension);
    d.doc = p.doc.c_str();
    d.flags = (p.required ? MG_PF_REQUIRED : 0u) | (p.knob ? MG_PF_KNOB : 0u) | (p.is_path ? MG_PF_PATH : 0u) |
              (p.default_value ? MG_PF_HAS_DEFAULT : 0u) | (p.example_value ? MG_PF_HAS_EXAMPLE : 0u) |
              (p.min_exclusive ? MG_PF_MIN_EXCLUSIVE : 0u) | (p.max_exclusive ? MG_PF_MAX_EXCLUSIVE : 0u);
    d.min = p.min;
    d.max = p.max;
    if (p.default_value) d.default_value = c_value(*p.default_value, p);
    if (p.example_value) d.example_value = c_value(*p.example_value, p);
    const auto& choices = names(p.choices);
    d.choices = choices.data();
    d.choice_count = choices.size();
    auto& fields = fields_.emplace_back();
    for (const ParamSpec& f : p.fields) fields.push_back(param_decl(f));
    d.fields = fields.data();
    d.field_count = fields.size();
    d.display_unit = p.display_unit.c_str();
    d.angle_frame = MG_NO_FRAME;
    d.range_reason = p.range_reason.empty() ? nullptr : p.range_reason.c_str();
    return d;
  }
  // `interfaces` gets the port's interface name (empty for values), in declaration order.
  mg_port_decl port_decl(const PortSpec& p, std::string_view plugin_id, std::deque<std::string>& interfaces) {
    mg_port_decl d{};
    d.struct_size = sizeof d;
    d.name = p.name.c_str();
    std::string& interface = interfaces.emplace_back();
    switch (p.kind) {
      case ValueKind::scalar: d.kind = MG_VALUE_SCALAR; break;
      case ValueKind::series: d.kind = MG_VALUE_SERIES; break;
      case ValueKind::table: d.kind = MG_VALUE_TABLE; break;
      case ValueKind::handle:
        d.kind = MG_VALUE_OBJECT;
        if (const SdkInterface* known = sdk_interface_of_kind(p.handle_kind)) {
          interface = known->name;
          d.interface_version = known->version;
        } else {
          interface = std::string(plugin_id) + "." + p.handle_kind;
          d.interface_version = 1;
        }
        d.interface = interface.c_str();
        break;
    }
    d.dim = c_dim(p.dimension);
    d.doc = p.doc.c_str();
    d.flags = (p.multiple ? MG_PORT_MULTIPLE : 0u) | (p.optional ? MG_PORT_OPTIONAL : 0u);
    d.display_unit = p.display_unit.c_str();
    d.label = optional_text(p.label);
    d.angle_frame = frame_index(p.angle_frame);
    d.presentation = presentation(p.presentation);
    return d;
  }

  // The host adopts a table or series: the plugin's Value (a shared pointer) keeps the arrays alive
  // until the host releases it.
  struct Holder {
    Value value;
    std::vector<mg_column> channels;
    std::vector<mg_mark> marks;
    std::vector<const char*> labels;
    mg_table table{};
    mg_series series{};
    static void release(void* self) { delete static_cast<Holder*>(self); }
  };
  static mg_column c_column(const Table::Column& c) { return {c.name.c_str(), c_dim(c.dimension), c.display_unit.c_str(), c.values.data()}; }

  // `v` is moved into what the host adopts.
  mg_status put_output(const mg_eval_suite_v1& suite, mg_eval_ctx* ctx, std::uint32_t index, Value& v) const {
    switch (v.kind()) {
      case ValueKind::scalar: suite.set_scalar(ctx, index, v.as_scalar()); return MG_OK;
      case ValueKind::series: {
        auto holder = std::make_unique<Holder>();
        holder->value = std::move(v);
        const Series& s = holder->value.as_series();
        for (const std::string& l : s.labels) holder->labels.push_back(l.c_str());
        holder->series = mg_series{sizeof(mg_series), s.values.size(), s.axis.data(), s.values.data(), c_dim(s.axis_dimension),
                                   s.labels.empty() ? nullptr : holder->labels.data(), {holder.get(), &Holder::release}};
        const mg_series* c = &holder->series;
        holder.release();  // the host releases it, also on refusal
        return suite.set_series(ctx, index, c);
      }
      case ValueKind::table: {
        auto holder = std::make_unique<Holder>();
        holder->value = std::move(v);
        const Table& t = holder->value.as_table();
        for (const Table::Column& c : t.channels) holder->channels.push_back(c_column(c));
        for (const Table::Mark& m : t.axis_marks) holder->marks.push_back({m.label.c_str(), m.value});
        holder->table = mg_table{sizeof(mg_table), t.axis.values.size(), c_column(t.axis), holder->channels.data(),
                                 holder->channels.size(),
                                 (t.closed_curve ? MG_TABLE_CLOSED_CURVE : 0u) | (t.histogram ? MG_TABLE_HISTOGRAM : 0u) |
                                     (t.turns_clockwise ? MG_TABLE_TURNS_CW : 0u),
                                 holder->marks.data(), holder->marks.size(), {holder.get(), &Holder::release}};
        const mg_table* c = &holder->table;
        holder.release();
        return suite.set_table(ctx, index, c);
      }
      case ValueKind::handle:  // one new reference, handed over to the host
        return suite.set_object(ctx, index, export_object(v.as_handle(), type_->info().type, output_interfaces_[index]));
    }
    return MG_ERR_UNSUPPORTED;
  }

  // This thread's sets for this type, made on first use.
  BridgeSets& thread_sets() const {
    auto& all = thread_bridge_sets();
    if (all.size() <= sets_index_) all.resize(sets_index_ + 1);
    if (!all[sets_index_]) all[sets_index_] = std::make_unique<BridgeSets>(type_->info());
    return *all[sets_index_];
  }

  static mg_status evaluate(const mg_node_type* self, const mg_eval_args* args, mg_eval_ctx* ctx) noexcept {
    const mg_eval_suite_v1& suite = *host_suites().eval;
    const auto& exported = *static_cast<const NodeTypeExport*>(self->impl);
    try {
      BridgeSets* sets = &exported.thread_sets();
      std::unique_ptr<BridgeSets> nested;  // an evaluation of this type inside one on this thread
      if (sets->busy) {
        nested = std::make_unique<BridgeSets>(exported.type_->info());
        sets = nested.get();
      }
      struct InUse {  // whatever happens, the sets hold nothing of this call afterwards
        BridgeSets& sets;
        explicit InUse(BridgeSets& s) : sets(s) { sets.busy = true; }
        ~InUse() {
          sets.release();
          sets.busy = false;
        }
      } const in_use(*sets);
      sets->load(*args, exported.input_interfaces_);
      SuiteContext context(exported.type_->info(), exported.output_index_, ctx,
                           MG_HAS_FIELD(args, mg_eval_args, wanted) ? args->wanted : nullptr);
      exported.type_->evaluate(sets->params, sets->inputs, sets->outputs, context);
      for (const std::string& note : sets->outputs.notes()) suite.note(ctx, c_text(note));
      return sets->put_outputs([&](std::uint32_t index, Value& v) { return exported.put_output(suite, ctx, index, v); });
    } catch (const NodeError& e) {
      suite.fail(ctx, c_text(e.parameter()), c_text(e.what()));
      return MG_ERR_NODE;
    } catch (const std::bad_alloc&) {
      return MG_ERR_NO_MEMORY;
    } catch (const std::exception& e) {
      suite.fail(ctx, {}, c_text(e.what()));
      return MG_ERR_INTERNAL;
    } catch (...) {
      suite.fail(ctx, {}, c_text("an exception that is not a std::exception"));
      return MG_ERR_INTERNAL;
    }
  }

  // The node type's own interfaces (node.h, query): mechgraph.node.forecast/1 over
  // NodeType::forecast (SDK 1.1, node_forecast.h) when the type has a forecast of its own (NULL
  // for one that keeps the default: the host counts it by the conventions without asking each
  // time; forecast_override.hpp); mechgraph.node.forecast_reads/1 (SDK 1.3,
  // node_forecast_reads.h) when it also implements ForecastReads; mechgraph.node.block/1 over
  // BlockEvaluation (SDK 1.2, node_block.h) when the type implements it; mechgraph.node.cxx/1
  // (SDK 1.5, node_cxx.h), the C++ type itself for a host of this C++ layer, unless this library
  // is built without the shortcut.
  static const void* query(const mg_node_type* self, const char* name, std::uint32_t version) noexcept {
    static const mg_node_forecast_v1 forecast_table{sizeof(mg_node_forecast_v1), &NodeTypeExport::forecast};
    const auto& exported = *static_cast<const NodeTypeExport*>(self->impl);
    if (name && version == 1 && std::strcmp(name, MG_NODE_FORECAST) == 0) return exported.has_forecast_ ? &forecast_table : nullptr;
    if (name && version == 1 && std::strcmp(name, MG_NODE_FORECAST_READS) == 0) return exported.has_reads_ ? &exported.reads_table_ : nullptr;
#if MECHGRAPH_SDK_CXX_SHORTCUT
    static const mg_node_cxx_v1 cxx_table{sizeof(mg_node_cxx_v1), cxx_abi_key, &NodeTypeExport::shared_type};
    if (name && version == 1 && std::strcmp(name, MG_NODE_CXX) == 0) return &cxx_table;
#endif
    return BlockExport<NodeTypeExport>::query(*exported.type_, name, version);
  }
  static const void* shared_type(const mg_node_type* self) noexcept {
    return &static_cast<const NodeTypeExport*>(self->impl)->type_;
  }
  // A sweep's budget asks this once per case and node: the parameters and sizes are refreshed in
  // this thread's sets (as evaluate's), so that a forecast allocates nothing but what the type's
  // own forecast does. Sets in use by an evaluation of this type further up this thread's stack
  // (a forecast made inside it) are left alone: this call makes its own.
  static mg_status forecast(const mg_node_type* self, const mg_param_value* params, const double* input_sizes,
                            mg_work_forecast* out, mg_text_sink driver) noexcept {
    try {
      const auto& exported = *static_cast<const NodeTypeExport*>(self->impl);
      BridgeSets* sets = &exported.thread_sets();
      std::unique_ptr<BridgeSets> nested;
      if (sets->busy) {
        nested = std::make_unique<BridgeSets>(exported.type_->info());
        sets = nested.get();
      }
      struct InUse {  // the parameters and sizes hold no object: nothing to release afterwards
        BridgeSets& sets;
        explicit InUse(BridgeSets& s) : sets(s) { sets.busy = true; }
        ~InUse() { sets.busy = false; }
      } const in_use(*sets);
      sets->load_forecast(params, input_sizes);
      const std::optional<WorkForecast> f = exported.type_->forecast(sets->params, sets->sizes);
      if (!f) return MG_ERR_UNSUPPORTED;
      *out = mg_work_forecast{f->items, f->memory, f->output_size};
      tell(driver, f->driver);
      return MG_OK;
    } catch (const std::bad_alloc&) {
      return MG_ERR_NO_MEMORY;
    } catch (...) {
      return MG_ERR_INTERNAL;
    }
  }

  std::shared_ptr<const NodeType> type_;
  std::size_t sets_index_;  // in thread_bridge_sets()
  bool has_forecast_;       // overrides NodeType::forecast (or cannot be told): answers mechgraph.node.forecast
  OutputIndex output_index_;  // the outputs by name, for SuiteContext::wanted
  bool has_reads_ = false;  // implements ForecastReads with declared names: answers mechgraph.node.forecast_reads
  std::vector<std::uint32_t> forecast_reads_;
  mg_node_forecast_reads_v1 reads_table_{};
  std::deque<std::string> input_interfaces_, output_interfaces_;
  std::deque<std::vector<const char*>> lists_;
  std::deque<std::vector<mg_param_decl>> fields_;
  std::deque<std::vector<mg_param_value>> values_;
  std::deque<std::vector<mg_record>> records_;
  std::vector<mg_param_decl> params_;
  std::vector<mg_port_decl> inputs_, outputs_;
  std::vector<mg_effect_decl> effects_;
  std::vector<mg_counter_decl> counters_;
  std::vector<mg_output_deps> deps_;
  std::vector<mg_angle_frame> frames_;
  std::vector<mg_note_decl> notes_;
  std::deque<mg_presentation> presentations_;
  std::deque<mg_channel_decl> axes_;
  std::deque<std::vector<mg_channel_decl>> channel_lists_;
  std::deque<std::vector<mg_code>> codes_;
  std::deque<std::vector<mg_xy_pair>> pairs_;
  std::deque<std::vector<mg_point_marks>> points_;
  mg_node_desc desc_{};
  mg_node_type c_type_{};
};

/// The body of mechgraph_plugin_entry_1 (MECHGRAPH_PLUGIN_1): called once per process.
inline const mg_plugin* plugin_entry_1(const mg_host* host, mg_text_sink why, const char* id, const char* version,
                                       NodeTypeList (*factory)()) noexcept {
  try {
    if (!host || host->sdk_major != MG_SDK_MAJOR) {
      tell(why, "this host's SDK has another major version than the plugin's 1");
      return nullptr;
    }
    host_suites().eval = static_cast<const mg_eval_suite_v1*>(host->fetch(host->host_data, MG_SUITE_EVAL, 1));
    if (!host_suites().eval) {
      tell(why, "this host offers no mechgraph.eval suite version 1");
      return nullptr;
    }
    // Kept until the process ends, never destroyed: the host holds pointers into them.
    static auto* exports = new std::vector<std::unique_ptr<NodeTypeExport>>();
    static auto* list = new std::vector<const mg_node_type*>();
    static mg_plugin plugin{};
    if (plugin.struct_size == 0) {
      for (auto& t : factory()) {
        if (!t) throw std::invalid_argument("the factory returned an empty node type");
        exports->push_back(std::make_unique<NodeTypeExport>(std::move(t), id));
        list->push_back(exports->back()->c_type());
      }
      plugin = mg_plugin{sizeof(mg_plugin), MG_SDK_MAJOR, MG_SDK_MINOR, id, version, MECHGRAPH_SDK_VERSION,
#if defined(__clang__)
                         "clang " __clang_version__,
#elif defined(__GNUC__)
                         "gcc " __VERSION__,
#else
                         "",
#endif
                         list->size(), list->data(), 0, nullptr};
    }
    return &plugin;
  } catch (const std::exception& e) {
    tell(why, e.what());
  } catch (...) {
    tell(why, "its node type factory threw something that is not a std::exception");
  }
  return nullptr;
}

}  // namespace mechgraph::detail
