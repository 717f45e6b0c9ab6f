#pragma once
// Parameter values as a node receives them: already parsed and converted to SI, range-checked
// against the node's ParamSpec, defaults filled in.
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph {

enum class ParamKind { number, integer, choice, text, number_list, record_list };

struct ParamValue;
using Record = std::map<std::string, ParamValue, std::less<>>;

struct ParamValue {
  ParamKind kind = ParamKind::number;
  double number = 0.0;               // number, integer
  std::string text;                  // choice, text
  std::vector<double> numbers;       // number_list
  std::vector<Record> records;       // record_list

  static ParamValue of_number(double v) { return {ParamKind::number, v, {}, {}, {}}; }
  static ParamValue of_integer(long v) { return {ParamKind::integer, static_cast<double>(v), {}, {}, {}}; }
  static ParamValue of_choice(std::string v) { return {ParamKind::choice, 0.0, std::move(v), {}, {}}; }
  static ParamValue of_text(std::string v) { return {ParamKind::text, 0.0, std::move(v), {}, {}}; }
  static ParamValue of_list(std::vector<double> v) { return {ParamKind::number_list, 0.0, {}, std::move(v), {}}; }
};

/// The parameters of one node instance. Accessors throw NodeError naming the parameter if it is
/// absent (only optional parameters without default can be absent).
class ParamSet {
 public:
  void set(std::string name, ParamValue value) { values_[std::move(name)] = std::move(value); }
  /// The value stored under `name`, made (as a default ParamValue) when absent: a host writes a
  /// swept parameter through it case after case. The reference lives as long as this set.
  ParamValue& slot(std::string_view name) {
    auto it = values_.find(name);
    return it != values_.end() ? it->second : values_.emplace(std::string(name), ParamValue{}).first->second;
  }
  bool has(std::string_view name) const { return values_.find(name) != values_.end(); }
  const ParamValue& get(std::string_view name) const;

  double number(std::string_view name) const { return get(name).number; }
  long integer(std::string_view name) const { return static_cast<long>(get(name).number); }
  const std::string& text(std::string_view name) const { return get(name).text; }
  const std::vector<double>& numbers(std::string_view name) const { return get(name).numbers; }
  const std::vector<Record>& records(std::string_view name) const { return get(name).records; }

  const std::map<std::string, ParamValue, std::less<>>& all() const { return values_; }

 private:
  std::map<std::string, ParamValue, std::less<>> values_;
};

}  // namespace mechgraph
