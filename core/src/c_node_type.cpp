#include "c_node_type.hpp"

#include "c_block_node_type.hpp"
#include "c_node_description.hpp"
#include "node_context.hpp"

#include <mechgraph/c/node_cxx.h>
#include <mechgraph/c/node_forecast.h>
#include <mechgraph/c/node_forecast_reads.h>
#include <mechgraph/c/sdk_lib.h>
#include <mechgraph/detail/object_bridge.hpp>
#include <mechgraph/cancellation.hpp>
#include <mechgraph/errors.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <new>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <vector>

namespace mechgraph::detail {
namespace {

std::string text(mg_str s) { return s.data ? std::string(s.data, s.size) : std::string(); }

}  // namespace
}  // namespace mechgraph::detail

// The per-call state behind the opaque mg_eval_ctx of host.h: what the eval suite reaches.
struct mg_eval_ctx {
  const mechgraph::NodeInfo& info;
  const std::vector<std::uint32_t>& output_versions;
  mechgraph::OutputSet& outputs;
  mechgraph::EvalContext& context;
  bool failed = false;
  std::string fail_parameter, fail_message;
  std::string defect;  // a broken contract of the boundary (an index out of range, a malformed table)
  std::vector<std::unique_ptr<std::byte[]>> scratch;

  void breaks(std::string what) {
    if (defect.empty()) defect = std::move(what);
  }
  // The output at `index` when it is declared with `kind`, else nullptr (and the defect noted,
  // unless even that fails for want of memory). Never throws: it runs inside C callbacks.
  const mechgraph::PortSpec* output(uint32_t index, mechgraph::ValueKind kind, const char* call) noexcept try {
    if (index >= info.outputs.size()) {
      breaks(std::string(call) + " was given output index " + std::to_string(index) + " of " +
             std::to_string(info.outputs.size()) + " declared outputs");
      return nullptr;
    }
    const mechgraph::PortSpec& port = info.outputs[index];
    if (port.kind != kind) {
      breaks(std::string(call) + " was used for output '" + port.name + "', declared as a " +
             std::string(mechgraph::to_string(port.kind)));
      return nullptr;
    }
    return &port;
  } catch (...) {
    return nullptr;
  }
};

namespace mechgraph::detail {
namespace {

// Releases an adopted array's owner once, whatever happens to its contents.
struct Adopted {
  mg_owner owner;
  ~Adopted() {
    if (owner.release) owner.release(owner.ctx);
  }
};

int32_t suite_effect(mg_eval_ctx* c, uint32_t index) {
  try {
    return index < c->info.effects.size() && c->context.effect(c->info.effects[index].name) ? 1 : 0;
  } catch (...) {
    return 0;
  }
}
int32_t suite_wanted(mg_eval_ctx* c, uint32_t index) {
  try {
    return index < c->info.outputs.size() && c->context.wanted(c->info.outputs[index].name) ? 1 : 0;
  } catch (...) {
    return 1;
  }
}
int32_t suite_cancelled(mg_eval_ctx*) { return cancellation_requested() ? 1 : 0; }
void suite_log(mg_eval_ctx* c, int32_t level, mg_str message) {
  try {
    c->context.log(level <= MG_LOG_DEBUG ? LogLevel::debug : level == MG_LOG_INFO ? LogLevel::info : LogLevel::warn,
                   text(message));
  } catch (...) {
  }
}
void suite_add_work(mg_eval_ctx* c, uint32_t index, double amount) {
  try {
    if (index >= c->info.work_counters.size())
      return c->breaks("add_work was given counter index " + std::to_string(index) + " of " +
                       std::to_string(c->info.work_counters.size()) + " declared work counters");
    c->context.report_work(c->info.work_counters[index], amount);
  } catch (const std::exception& e) {
    c->breaks(e.what());
  }
}
void suite_note(mg_eval_ctx* c, mg_str note) {
  try {
    c->outputs.note(text(note));
  } catch (const std::exception& e) {
    c->breaks(e.what());
  }
}
void suite_fail(mg_eval_ctx* c, mg_str parameter, mg_str message) {
  try {
    if (c->failed) return;  // the first failure is the one a user reads
    c->failed = true;
    c->fail_parameter = text(parameter);
    c->fail_message = text(message);
  } catch (...) {
  }
}
void suite_set_scalar(mg_eval_ctx* c, uint32_t index, double value) {
  try {
    if (const PortSpec* port = c->output(index, ValueKind::scalar, "set_scalar")) c->outputs.set_scalar(port->name, value);
  } catch (const std::exception& e) {
    c->breaks(e.what());
  }
}
mg_status suite_set_series(mg_eval_ctx* c, uint32_t index, const mg_series* s) {
  const Adopted adopted{s ? s->owner : mg_owner{nullptr, nullptr}};
  try {
    const PortSpec* port = c->output(index, ValueKind::series, "set_series");
    if (!port) return MG_ERR_BAD_ARGUMENT;
    if (!s || s->struct_size < sizeof(mg_series) || (s->size > 0 && (!s->axis || !s->values))) {
      c->breaks("set_series was given a malformed mg_series for output '" + port->name + "'");
      return MG_ERR_BAD_ARGUMENT;
    }
    Series out;
    out.axis.assign(s->axis, s->axis + s->size);
    out.values.assign(s->values, s->values + s->size);
    out.axis_dimension = from_c_dim(s->axis_dim, "output '" + port->name + "'");
    if (s->labels)
      for (size_t i = 0; i < s->size; ++i) out.labels.emplace_back(s->labels[i] ? s->labels[i] : "");
    c->outputs.set(port->name, Value::series(std::move(out)));
    return MG_OK;
  } catch (const std::bad_alloc&) {
    return MG_ERR_NO_MEMORY;
  } catch (const std::exception& e) {
    c->breaks(e.what());
    return MG_ERR_BAD_ARGUMENT;
  }
}
Table::Column column(const mg_column& c, size_t rows, const std::string& what) {
  if (!c.name) throw std::invalid_argument(what + " has a column without a name");
  if (rows > 0 && !c.values) throw std::invalid_argument(what + ": column '" + std::string(c.name) + "' has no values");
  Table::Column out{c.name, from_c_dim(c.dim, what + " column '" + c.name + "'"), {}, c.display_unit ? c.display_unit : ""};
  out.values.assign(c.values, c.values + rows);
  return out;
}
mg_status suite_set_table(mg_eval_ctx* c, uint32_t index, const mg_table* t) {
  const Adopted adopted{t ? t->owner : mg_owner{nullptr, nullptr}};
  try {
    const PortSpec* port = c->output(index, ValueKind::table, "set_table");
    if (!port) return MG_ERR_BAD_ARGUMENT;
    const std::string what = "set_table for output '" + port->name + "'";
    if (!t || t->struct_size < sizeof(mg_table) || (t->channel_count > 0 && !t->channels) || (t->mark_count > 0 && !t->marks)) {
      c->breaks(what + " was given a malformed mg_table");
      return MG_ERR_BAD_ARGUMENT;
    }
    Table out;
    out.axis = column(t->axis, t->rows, what);
    for (size_t i = 0; i < t->channel_count; ++i) out.channels.push_back(column(t->channels[i], t->rows, what));
    out.closed_curve = (t->flags & MG_TABLE_CLOSED_CURVE) != 0;
    out.histogram = (t->flags & MG_TABLE_HISTOGRAM) != 0;
    out.turns_clockwise = (t->flags & MG_TABLE_TURNS_CW) != 0;
    for (size_t i = 0; i < t->mark_count; ++i)
      out.axis_marks.push_back({t->marks[i].label ? t->marks[i].label : "", t->marks[i].value});
    c->outputs.set(port->name, Value::table(std::move(out)));
    return MG_OK;
  } catch (const std::bad_alloc&) {
    return MG_ERR_NO_MEMORY;
  } catch (const std::exception& e) {
    c->breaks(e.what());
    return MG_ERR_BAD_ARGUMENT;
  }
}
mg_status suite_set_object(mg_eval_ctx* c, uint32_t index, const mg_object* o) {
  if (!o || !o->vtbl || !o->vtbl->retain || !o->vtbl->release || !o->vtbl->query) {
    c->breaks("set_object was given no object, or one whose vtable lacks retain, release or query");
    return MG_ERR_BAD_ARGUMENT;
  }
  // The reference handed over is released here; the C++ view takes its own (or, for an object this
  // host exported, is the host's C++ object again).
  struct HandedOver {
    const mg_object* o;
    ~HandedOver() { o->vtbl->release(o); }
  } const handed_over{o};
  const PortSpec* port = c->output(index, ValueKind::handle, "set_object");
  if (!port) return MG_ERR_BAD_ARGUMENT;
  try {
    c->outputs.set(port->name, Value::handle(import_object(o, interface_of_port(*port), c->output_versions[index])));
    return MG_OK;
  } catch (const std::bad_alloc&) {
    return MG_ERR_NO_MEMORY;
  } catch (const std::exception& e) {
    c->breaks("set_object for output '" + port->name + "': " + e.what());
    return MG_ERR_BAD_ARGUMENT;
  }
}
void* suite_scratch(mg_eval_ctx* c, size_t bytes, size_t align) {
  try {
    if (align == 0 || (align & (align - 1)) != 0 || align > 4096 || bytes > SIZE_MAX - align) return nullptr;
    auto block = std::make_unique_for_overwrite<std::byte[]>(bytes + align);
    void* p = block.get();
    size_t space = bytes + align;
    void* aligned = std::align(align, bytes, p, space);
    c->scratch.push_back(std::move(block));
    return aligned;
  } catch (...) {
    return nullptr;
  }
}

const mg_eval_suite_v1 eval_suite{sizeof(mg_eval_suite_v1), &suite_effect,     &suite_wanted,     &suite_cancelled,
                                  &suite_log,               &suite_add_work,   &suite_note,       &suite_fail,
                                  &suite_set_scalar,        &suite_set_series, &suite_set_table,  &suite_set_object,
                                  &suite_scratch};

// The C views of one evaluation's parameters and inputs, over the host's own storage (nothing
// copied but the small descriptors).
class CallViews {
 public:
  mg_param_value param(const ParamValue& v, const ParamSpec& spec) {
    mg_param_value out{};
    out.present = 1;
    switch (spec.kind) {
      case ParamKind::number: out.kind = MG_PARAM_NUMBER; out.number = v.number; break;
      case ParamKind::integer: out.kind = MG_PARAM_INTEGER; out.number = v.number; break;
      case ParamKind::choice: out.kind = MG_PARAM_CHOICE; out.text = {v.text.data(), v.text.size()}; break;
      case ParamKind::text: out.kind = MG_PARAM_TEXT; out.text = {v.text.data(), v.text.size()}; break;
      case ParamKind::number_list:
        out.kind = MG_PARAM_NUMBER_LIST;
        out.numbers = v.numbers.data();
        out.number_count = v.numbers.size();
        break;
      case ParamKind::record_list: {
        out.kind = MG_PARAM_RECORD_LIST;
        std::vector<mg_record>& records = add(stores().records_);
        for (const Record& r : v.records) {
          std::vector<mg_param_value>& fields = add(stores().fields_);
          for (const ParamSpec& f : spec.fields) {
            const auto it = r.find(f.name);
            fields.push_back(it != r.end() ? param(it->second, f) : absent(f));
          }
          records.push_back({fields.data(), fields.size()});
        }
        out.records = records.data();
        out.record_count = records.size();
        break;
      }
    }
    return out;
  }
  static mg_param_value absent(const ParamSpec& spec) {
    mg_param_value out{};
    out.kind = static_cast<int32_t>(spec.kind) + 1;  // ParamKind's order is MG_PARAM_*'s, from 1
    return out;
  }
  mg_value value(const Value& v) {
    mg_value out{};
    switch (v.kind()) {
      case ValueKind::scalar: out.kind = MG_VALUE_SCALAR; out.u.scalar = v.as_scalar(); break;
      case ValueKind::series: {
        const Series& s = v.as_series();
        mg_series& c = add(stores().series_);
        c = mg_series{sizeof(mg_series), s.values.size(), s.axis.data(), s.values.data(), to_c_dim(s.axis_dimension), nullptr, {}};
        if (!s.labels.empty()) {
          std::vector<const char*>& labels = add(stores().labels_);
          for (const std::string& l : s.labels) labels.push_back(l.c_str());
          c.labels = labels.data();
        }
        out.kind = MG_VALUE_SERIES;
        out.u.series = &c;
        break;
      }
      case ValueKind::table: {
        const Table& t = v.as_table();
        std::vector<mg_column>& channels = add(stores().columns_);
        for (const Table::Column& col : t.channels) channels.push_back(column(col));
        std::vector<mg_mark>& marks = add(stores().marks_);
        for (const Table::Mark& m : t.axis_marks) marks.push_back({m.label.c_str(), m.value});
        mg_table& c = add(stores().tables_);
        c = mg_table{sizeof(mg_table), t.axis.values.size(), column(t.axis), channels.data(), channels.size(),
                     (t.closed_curve ? MG_TABLE_CLOSED_CURVE : 0u) | (t.histogram ? MG_TABLE_HISTOGRAM : 0u) |
                         (t.turns_clockwise ? MG_TABLE_TURNS_CW : 0u),
                     marks.data(), marks.size(), {}};
        out.kind = MG_VALUE_TABLE;
        out.u.table = &c;
        break;
      }
      case ValueKind::handle: {
        out.kind = MG_VALUE_OBJECT;
        // A foreign object's original, or a pre-1.0 plugin's C++ object exported for the call.
        out.u.object = stores().objects_.emplace_back(std::make_unique<ObjectReference>(export_object(v.as_handle(), "", "")))->object;
        break;
      }
    }
    return out;
  }

 private:
  static mg_column column(const Table::Column& c) {
    return {c.name.c_str(), to_c_dim(c.dimension), c.display_unit.c_str(), c.values.data()};
  }
  // Stable addresses, and no allocation at all for a call that needs none of them (a std::deque
  // allocates when it is made).
  template <class T>
  static T& add(std::vector<std::unique_ptr<T>>& store) {
    return *store.emplace_back(std::make_unique<T>());
  }
  // Owns one reference for the call.
  struct ObjectReference {
    const mg_object* object;
    explicit ObjectReference(const mg_object* o) : object(o) {}
    ~ObjectReference() { object->vtbl->release(object); }
  };
  // Made only when a call needs one of them (a record list, a series, a table, an object): a call
  // of scalars and numbers neither makes nor destroys any.
  struct Stores {
    std::vector<std::unique_ptr<std::vector<mg_record>>> records_;
    std::vector<std::unique_ptr<std::vector<mg_param_value>>> fields_;
    std::vector<std::unique_ptr<mg_series>> series_;
    std::vector<std::unique_ptr<std::vector<const char*>>> labels_;
    std::vector<std::unique_ptr<std::vector<mg_column>>> columns_;
    std::vector<std::unique_ptr<std::vector<mg_mark>>> marks_;
    std::vector<std::unique_ptr<mg_table>> tables_;
    std::vector<std::unique_ptr<ObjectReference>> objects_;
  };
  Stores& stores() {
    if (!stores_) stores_ = std::make_unique<Stores>();
    return *stores_;
  }
  std::unique_ptr<Stores> stores_;
};

// `n` elements of one call's C arguments: on the stack up to N (no allocation for the usual node),
// on the heap beyond. Elements are left uninitialised: the caller writes each one.
template <class T, std::size_t N>
class CallArray {
 public:
  explicit CallArray(std::size_t n) : data_(n <= N ? stack_.data() : (heap_ = std::make_unique_for_overwrite<T[]>(n)).get()) {}
  CallArray(const CallArray&) = delete;
  CallArray& operator=(const CallArray&) = delete;
  T* data() { return data_; }
  T& operator[](std::size_t i) { return data_[i]; }

 private:
  std::array<T, N> stack_;
  std::unique_ptr<T[]> heap_;
  T* data_;
};

// Indices of `items` in the order of their names: a set (a std::map by name) and the declaration
// are then matched in one pass, with no lookup per name.
template <class Spec>
std::vector<std::size_t> by_name(const std::vector<Spec>& items) {
  std::vector<std::size_t> order(items.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return items[a].name < items[b].name; });
  return order;
}

// For each declared item (by_name order), the entry of `set` (a std::map by name) with its name,
// or nullptr: f(declared index, const mapped_type* or nullptr).
// The set usually holds exactly the declared names, so each is first tried for equality with the
// next entry (a length and one memcmp), and only a mismatch is ordered.
template <class Spec, class Map, class F>
void match_by_name(const std::vector<Spec>& items, const std::vector<std::size_t>& order, const Map& set, F&& f) {
  auto it = set.begin();
  for (const std::size_t k : order) {
    const std::string& name = items[k].name;
    if (it != set.end() && it->first.size() == name.size() && std::memcmp(it->first.data(), name.data(), name.size()) == 0) {
      f(k, &it->second);
      ++it;
      continue;
    }
    while (it != set.end() && it->first < name) ++it;
    if (it != set.end() && it->first == name) {
      f(k, &it->second);
      ++it;
    } else {
      f(k, nullptr);
    }
  }
}

// The node type's mechgraph.node.forecast/1 table (node_forecast.h), asked for once, or nullptr
// when it has none: a 1.0 writer's mg_node_type may end before `query`, query may be NULL or
// answer NULL, and a table without its function counts as none.
const mg_node_forecast_v1* node_forecast(const mg_node_type& type) {
  if (!MG_HAS_FIELD(&type, mg_node_type, query) || !type.query) return nullptr;
  const auto* table = static_cast<const mg_node_forecast_v1*>(type.query(&type, MG_NODE_FORECAST, 1));
  return table && MG_HAS_FIELD(table, mg_node_forecast_v1, forecast) && table->forecast ? table : nullptr;
}

// The names of the parameters its forecast reads (mechgraph.node.forecast_reads/1, SDK 1.3), or
// none when it does not say, says it with an index out of range, or has no forecast to describe.
std::optional<std::vector<std::string>> node_forecast_reads(const mg_node_type& type, const NodeInfo& info, bool has_forecast) {
  if (!has_forecast || !MG_HAS_FIELD(&type, mg_node_type, query) || !type.query) return std::nullopt;
  const auto* table = static_cast<const mg_node_forecast_reads_v1*>(type.query(&type, MG_NODE_FORECAST_READS, 1));
  if (!table || !MG_HAS_FIELD(table, mg_node_forecast_reads_v1, param_count) || (table->param_count && !table->params))
    return std::nullopt;
  std::vector<std::string> names;
  for (std::size_t k = 0; k < table->param_count; ++k) {
    if (table->params[k] >= info.params.size()) return std::nullopt;
    names.push_back(info.params[table->params[k]].name);
  }
  return names;
}

class CNodeType final : public NodeType, public ForecastReads {
 public:
  CNodeType(const mg_node_type& type, CNodeDeclaration declaration)
      : type_(type),
        forecast_(node_forecast(type)),
        info_(std::move(declaration.info)),
        params_by_name_(by_name(info_.params)),
        inputs_by_name_(by_name(info_.inputs)),
        input_versions_(std::move(declaration.input_interface_versions)),
        output_versions_(std::move(declaration.output_interface_versions)),
        forecast_reads_(node_forecast_reads(type, info_, forecast_ != nullptr)) {}
  const NodeInfo& info() const override { return info_; }
  std::optional<std::vector<std::string>> forecast_reads() const override { return forecast_reads_; }
  PortInterfaceVersions interface_versions() const { return {input_versions_, output_versions_}; }

  // Its own forecast when it offers mechgraph.node.forecast/1 (SDK 1.1), else none: the host then
  // counts by the conventions (work_estimate.hpp).
  std::optional<WorkForecast> forecast(const ParamSet& params, const InputSizes& sizes) const override {
    if (!forecast_) return std::nullopt;
    CallViews views;
    CallArray<mg_param_value, 16> c_params(info_.params.size());
    param_views(params, views, c_params.data());
    return forecast_with(c_params.data(), sizes);
  }
  bool has_forecast() const { return forecast_ != nullptr; }
  // The parameters' entries in `params` by declared index (nullptr: absent), for BoundForecast.
  std::vector<const ParamValue*> matched_params(const ParamSet& params) const {
    std::vector<const ParamValue*> out(info_.params.size(), nullptr);
    match_by_name(info_.params, params_by_name_, params.all(), [&](std::size_t k, const ParamValue* value) { out[k] = value; });
    return out;
  }
  // c_params[k] for the matched entries (one per declared parameter), as param_views makes them.
  void matched_views(const std::vector<const ParamValue*>& values, CallViews& views, mg_param_value* c_params) const {
    for (std::size_t k = 0; k < values.size(); ++k)
      c_params[k] = values[k] ? views.param(*values[k], info_.params[k]) : CallViews::absent(info_.params[k]);
  }
  // The forecast of parameters already in C (views that live through the call); without its
  // driver's text when `with_driver` is false (a sink that drops it: nothing allocated).
  std::optional<WorkForecast> forecast_with(const mg_param_value* c_params, const InputSizes& sizes, bool with_driver = true) const {
    CallArray<double, 8> c_sizes(info_.inputs.size());
    match_by_name(info_.inputs, inputs_by_name_, sizes, [&](std::size_t k, const double* size) { c_sizes[k] = size ? *size : 0.0; });
    mg_work_forecast out{};
    std::string driver;
    const mg_text_sink dropped{nullptr, [](void*, const char*, size_t) {}};
    if (forecast_->forecast(&type_, c_params, c_sizes.data(), &out, with_driver ? string_sink(&driver) : dropped) != MG_OK)
      return std::nullopt;
    return WorkForecast{out.items, out.memory, out.output_size, std::move(driver)};
  }

  // The C arguments are views over the host's sets, on the stack for the usual node; the sets are
  // matched with the declaration in one pass each (by_name), not looked up name by name.
  void evaluate(const ParamSet& params, const InputSet& inputs, OutputSet& outputs, EvalContext& context) const override {
    CallViews views;
    CallArray<mg_param_value, 16> c_params(info_.params.size());
    param_views(params, views, c_params.data());
    const std::size_t ports = info_.inputs.size();
    CallArray<const std::vector<Value>*, 8> connected(ports);
    std::size_t count = 0;
    match_by_name(info_.inputs, inputs_by_name_, inputs.all(), [&](std::size_t k, const std::vector<Value>* values) {
      connected[k] = values;
      count += values ? values->size() : 0;
    });
    CallArray<mg_value, 16> values(count);
    CallArray<mg_input, 8> c_inputs(ports);
    for (std::size_t i = 0, next = 0; i < ports; ++i) {
      c_inputs[i] = {values.data() + next, connected[i] ? connected[i]->size() : 0};
      if (connected[i])
        for (const Value& v : *connected[i]) values[next++] = views.value(v);
    }
    // What is read downstream, by declared index (SDK 1.4): the graph node's mask when the host's
    // own context evaluates it, else asked output by output.
    const std::int32_t* wanted = typeid(context) == typeid(NodeContext) ? static_cast<const NodeContext&>(context).wanted_mask() : nullptr;
    CallArray<std::int32_t, 32> asked(wanted ? 0 : info_.outputs.size());
    if (!wanted) {
      for (std::size_t i = 0; i < info_.outputs.size(); ++i) asked[i] = context.wanted(info_.outputs[i].name) ? 1 : 0;
      wanted = asked.data();
    }
    const mg_eval_args args{sizeof(mg_eval_args), c_params.data(), c_inputs.data(), wanted};
    mg_eval_ctx call{info_, output_versions_, outputs, context, false, {}, {}, {}, {}};
    const mg_status status = type_.evaluate(&type_, &args, &call);
    if (!call.defect.empty())
      throw std::runtime_error("broke the C boundary's contract: " + call.defect + " (a defect of its plugin)");
    switch (status) {
      case MG_OK:
        if (call.failed) throw std::runtime_error("called fail() (" + call.fail_message + ") but returned MG_OK (a defect of its plugin)");
        return;
      case MG_ERR_NODE:
        throw NodeError(call.fail_parameter, call.fail_message.empty() ? std::string("failed without saying why (MG_ERR_NODE)")
                                                                       : call.fail_message);
      case MG_ERR_CANCELLED: throw std::runtime_error("stopped: the evaluation was cancelled");
      case MG_ERR_NO_MEMORY: throw std::bad_alloc();
      default:
        throw std::runtime_error("returned " + std::string(mg_status_name(status)) +
                                 (call.fail_message.empty() ? std::string() : " (" + call.fail_message + ")") +
                                 " (a defect of its plugin)");
    }
  }

 private:
  // c_params[i] for each declared parameter i.
  void param_views(const ParamSet& params, CallViews& views, mg_param_value* c_params) const {
    match_by_name(info_.params, params_by_name_, params.all(), [&](std::size_t k, const ParamValue* value) {
      c_params[k] = value ? views.param(*value, info_.params[k]) : CallViews::absent(info_.params[k]);
    });
  }

  const mg_node_type& type_;
  const mg_node_forecast_v1* forecast_;
  NodeInfo info_;
  std::vector<std::size_t> params_by_name_, inputs_by_name_;
  std::vector<std::uint32_t> input_versions_, output_versions_;
  std::optional<std::vector<std::string>> forecast_reads_;
};

}  // namespace

const mg_eval_suite_v1& c_eval_suite() { return eval_suite; }

std::string interface_of_port(const PortSpec& port) {
  if (const SdkInterface* known = sdk_interface_of_kind(port.handle_kind)) return known->name;
  return port.handle_kind;
}

bool runs_through_c(const NodeType& type) {
  return c_type_behind_blocks(type) != nullptr || dynamic_cast<const CNodeType*>(&type) != nullptr;
}

namespace {
// Whether reading the C description of `p` (c_node_description.cpp) gives `p` back: not for a
// required parameter with a default (read as not required), nor for a record field that is one.
bool survives_c(const ParamSpec& p) {
  if (p.required && p.default_value) return false;
  return std::all_of(p.fields.begin(), p.fields.end(), [](const ParamSpec& f) { return survives_c(f); });
}
// The same for a port: a private interface is read as "PLUGIN.kind", a table's dimension and a
// value's interface are not read at all.
bool survives_c(const PortSpec& p) {
  if (p.kind == ValueKind::handle) return sdk_interface_of_kind(p.handle_kind) != nullptr;
  if (!p.handle_kind.empty()) return false;
  return p.kind != ValueKind::table || p.dimension.dimensionless();
}
}  // namespace

bool c_type_offers_forecast(const mg_node_type& type) { return node_forecast(type) != nullptr; }

std::shared_ptr<const NodeType> same_cxx_node_type(const mg_node_type& type) {
  if (type.struct_size < offsetof(mg_node_type, query) + sizeof type.query || !type.query) return nullptr;
  const auto* table = static_cast<const mg_node_cxx_v1*>(type.query(&type, MG_NODE_CXX, 1));
  if (!table || table->struct_size < sizeof(mg_node_cxx_v1) || !table->shared_type || !is_own_cxx_abi_key(table->abi_key))
    return nullptr;
  const void* shared = table->shared_type(&type);
  if (!shared) return nullptr;
  std::shared_ptr<const NodeType> cxx = *static_cast<const std::shared_ptr<const NodeType>*>(shared);
  if (!cxx) return nullptr;
  // Taken only when the host would read the same declaration from C: the type is then described
  // and presented alike either way. A type that throws from info() is left to the C path, whose
  // reading says what is wrong.
  try {
    const NodeInfo& info = cxx->info();
    for (const std::vector<PortSpec>* ports : {&info.inputs, &info.outputs})
      for (const PortSpec& port : *ports)
        if (!survives_c(port)) return nullptr;
    for (const ParamSpec& param : info.params)
      if (!survives_c(param)) return nullptr;
  } catch (...) {
    return nullptr;
  }
  return cxx;
}

std::shared_ptr<const NodeType> make_c_node_type(const mg_node_type& type, const std::string& where, bool through_c) {
  if (type.struct_size < offsetof(mg_node_type, query))
    throw PluginError(where + ": a node type's mg_node_type is " + std::to_string(type.struct_size) +
                      " bytes (struct_size), shorter than the " + std::to_string(offsetof(mg_node_type, query)) +
                      " bytes every SDK 1.x writer fills; a defect of the plugin");
  if (!type.evaluate) throw PluginError(where + ": a node type has no evaluate function");
  if (!through_c)
    if (std::shared_ptr<const NodeType> itself = same_cxx_node_type(type)) return itself;
  return with_c_blocks(std::make_shared<const CNodeType>(type, c_node_declaration(type, where)), type);
}

namespace {
// The entries are matched with the declaration once, and their C views made once; each call
// refreshes in place what a set written in place can change (a number; a text's or a list's
// address and length), with no allocation. A record list's views are made again on each call (they
// live through it, as in evaluate).
class CBoundForecast final : public BoundForecast {
 public:
  CBoundForecast(const CNodeType& type, const ParamSet& params)
      : type_(type), values_(type.matched_params(params)), c_params_(values_.size()) {
    CallViews views;
    type_.matched_views(values_, views, c_params_.data());
    for (std::size_t k = 0; k < values_.size(); ++k)
      if (values_[k] && type_.info().params[k].kind == ParamKind::record_list) records_ = true;
  }
  std::optional<WorkForecast> operator()(const InputSizes& sizes) override {
    if (records_) {
      CallViews views;
      type_.matched_views(values_, views, c_params_.data());
      return type_.forecast_with(c_params_.data(), sizes, false);
    }
    for (std::size_t k = 0; k < values_.size(); ++k) {
      const ParamValue* v = values_[k];
      if (!v) continue;  // absent: its view says so, and a set cannot gain an entry in place
      mg_param_value& c = c_params_[k];  // the fields CallViews::param fills for its kind
      switch (c.kind) {
        case MG_PARAM_NUMBER:
        case MG_PARAM_INTEGER: c.number = v->number; break;
        case MG_PARAM_CHOICE:
        case MG_PARAM_TEXT: c.text = {v->text.data(), v->text.size()}; break;
        case MG_PARAM_NUMBER_LIST:
          c.numbers = v->numbers.data();
          c.number_count = v->numbers.size();
          break;
        default: break;
      }
    }
    return type_.forecast_with(c_params_.data(), sizes, false);
  }

 private:
  const CNodeType& type_;
  std::vector<const ParamValue*> values_;  // into the bound set, by declared index
  std::vector<mg_param_value> c_params_;
  bool records_ = false;  // a record list is present: views made on each call
};
}  // namespace

std::unique_ptr<BoundForecast> bind_forecast(const NodeType& type, const ParamSet& params) {
  if (const NodeType* behind = c_type_behind_blocks(type)) return bind_forecast(*behind, params);
  const auto* c = dynamic_cast<const CNodeType*>(&type);
  if (!c || !c->has_forecast()) return nullptr;
  return std::make_unique<CBoundForecast>(*c, params);
}

std::optional<std::vector<std::string>> forecast_reads(const NodeType& type) {
  // An SDK 1.x type's host view answers from mechgraph.node.forecast_reads/1 (CNodeType, and the
  // block view in front of it); a C++ type from the plugin's own class.
  const auto* reads = dynamic_cast<const ForecastReads*>(&type);
  if (!reads) return std::nullopt;
  try {
    std::optional<std::vector<std::string>> names = reads->forecast_reads();
    if (!names) return std::nullopt;
    for (const std::string& name : *names)
      if (!type.info().find_param(name)) return std::nullopt;
    return names;
  } catch (...) {
    return std::nullopt;  // as a forecast that throws: asked case by case
  }
}

PortInterfaceVersions port_interface_versions(const NodeType& type) {
  if (const NodeType* behind = c_type_behind_blocks(type)) return port_interface_versions(*behind);
  if (const auto* c = dynamic_cast<const CNodeType*>(&type)) return c->interface_versions();
  const auto bridged = [](const std::vector<PortSpec>& ports) {
    std::vector<std::uint32_t> versions;
    for (const PortSpec& p : ports) {
      const SdkInterface* known = p.kind == ValueKind::handle ? sdk_interface_of_kind(p.handle_kind) : nullptr;
      versions.push_back(known ? known->version : 0);
    }
    return versions;
  };
  return {bridged(type.info().inputs), bridged(type.info().outputs)};
}

}  // namespace mechgraph::detail
