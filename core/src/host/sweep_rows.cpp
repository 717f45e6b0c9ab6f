#include <mechgraph/host/sweep_rows.hpp>

#include <mechgraph/host/angle_reference.hpp>
#include <mechgraph/host/exit_codes.hpp>
#include <mechgraph/host/usage_error.hpp>
#include <mechgraph/shown_number.hpp>

#include <mechgraph/csv.hpp>
#include <mechgraph/json_writer.hpp>
#include <mechgraph/units.hpp>

#include <mechgraph/sweep/case_table.hpp>

#include <algorithm>
#include <charconv>
#include <type_traits>
#include <cmath>
#include <limits>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <sstream>

namespace mechgraph::host {
namespace {

std::string with_unit(const std::string& name, const std::string& unit) {
  return unit.empty() || unit == "1" ? name : name + " [" + unit + "]";
}

// The shortest text that reads back to the same double (std::to_chars: exact, and fast).
std::string exact(double x) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, end);
}

// The unit a port's values are shown in: its display unit, else SI; with the angle its port
// counts when that unit holds degrees ("deg (shaft)", angle_reference.hpp: the report's rule).
std::string unit_of(const Graph& graph, const RequestedOutput& o) {
  const std::string unit = o.spec->display_unit.empty() ? o.spec->dimension.si_unit() : o.spec->display_unit;
  return o.node < graph.nodes.size() ? unit_with_reference(unit, angle_reference(graph.nodes[o.node].info(), *o.spec)) : unit;
}

// A flat JSON object as the rows are written ({"key":value,...}; values strings, numbers, null,
// true or false; nothing nested), read into keys, cell texts and whether each value was a number
// or null (`plain`). A small reader of its own: strict JSON (yaml-cpp would take YAML too) and
// fast enough for merge to check millions of rows. False for anything else.
class FlatJson {
 public:
  explicit FlatJson(std::string_view text) : s_(text) {}
  bool read(std::vector<std::string>& keys, std::vector<std::string>& cells, std::vector<bool>& plain) {
    space();
    if (!eat('{')) return false;
    space();
    if (eat('}')) return end();
    for (;;) {
      std::string key, cell;
      bool number = false;
      space();
      if (!string(key)) return false;
      space();
      if (!eat(':')) return false;
      space();
      if (!value(cell, number)) return false;
      keys.push_back(std::move(key));
      cells.push_back(std::move(cell));
      plain.push_back(number);
      space();
      if (eat('}')) return end();
      if (!eat(',')) return false;
    }
  }

 private:
  bool end() {
    space();
    return i_ == s_.size();
  }
  void space() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\r')) ++i_;
  }
  bool eat(char c) {
    if (i_ < s_.size() && s_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  bool word(std::string_view w) {
    if (s_.substr(i_, w.size()) != w) return false;
    i_ += w.size();
    return true;
  }
  static void utf8(std::string& out, unsigned long cp) {
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xC0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xE0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }
  bool hex4(unsigned long& cp) {
    if (i_ + 4 > s_.size()) return false;
    cp = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = s_[i_++];
      const int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
      if (d < 0) return false;
      cp = cp * 16 + static_cast<unsigned long>(d);
    }
    return true;
  }
  bool string(std::string& out) {
    if (!eat('"')) return false;
    while (i_ < s_.size()) {
      const char c = s_[i_++];
      if (c == '"') return true;
      if (static_cast<unsigned char>(c) < 0x20) return false;
      if (c != '\\') {
        out += c;
        continue;
      }
      if (i_ >= s_.size()) return false;
      const char e = s_[i_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          unsigned long cp = 0;
          if (!hex4(cp)) return false;
          if (cp >= 0xD800 && cp < 0xDC00) {  // a surrogate pair
            unsigned long low = 0;
            if (!word("\\u") || !hex4(low) || low < 0xDC00 || low >= 0xE000) return false;
            cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
          } else if (cp >= 0xDC00 && cp < 0xE000) {
            return false;
          }
          utf8(out, cp);
          break;
        }
        default: return false;
      }
    }
    return false;
  }
  // A JSON number: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?
  bool number(std::string& out) {
    const std::size_t start = i_;
    eat('-');
    auto digits = [&] {
      const std::size_t from = i_;
      while (i_ < s_.size() && s_[i_] >= '0' && s_[i_] <= '9') ++i_;
      return i_ > from;
    };
    if (eat('0')) {
    } else if (!digits()) {
      return false;
    }
    if (eat('.') && !digits()) return false;
    if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
      ++i_;
      if (!eat('+')) eat('-');
      if (!digits()) return false;
    }
    out.assign(s_.substr(start, i_ - start));
    return true;
  }
  bool value(std::string& out, bool& plain) {
    if (i_ >= s_.size()) return false;
    const char c = s_[i_];
    plain = false;
    if (c == '"') return string(out);
    if (word("true")) return out = "true", true;
    if (word("false")) return out = "false", true;
    plain = true;
    if (word("null")) return true;
    return number(out);
  }
  std::string_view s_;
  std::size_t i_ = 0;
};

// The names the rows reserve: no input or output column may take them (JSON keys are unique).
const std::vector<std::string> reserved_columns = {"case", "exit", "error"};

}  // namespace

std::optional<double> finite_number_in_cell(std::string_view text) {
  if (text.empty() || text.front() == '+') return std::nullopt;
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

void SweepRows::make_unique(std::vector<std::string>& names, const std::vector<std::string>& taken, const std::string& prefix) {
  std::set<std::string> used(taken.begin(), taken.end());
  for (std::string& n : names) {
    while (used.count(n)) n = prefix + n;
    used.insert(n);
  }
}

std::vector<std::string> SweepRows::input_headers() const {
  std::vector<std::string> names;
  for (const SweepVariable& v : table_.variables) names.push_back(with_unit(v.name, v.unit));
  make_unique(names, reserved_columns, "in.");
  return names;
}

int exit_code_of(CaseFailure failure) {
  switch (failure) {
    case CaseFailure::none: return ok;
    case CaseFailure::scene: return usage_error;
    case CaseFailure::evaluation: return evaluation_error;
  }
  return evaluation_error;
}

std::string sweep_column_name(const Graph& graph, std::size_t output) {
  const RequestedOutput& o = graph.outputs.at(output);
  return with_unit(o.label, unit_of(graph, o));
}

SweepRows::SweepRows(const Graph& graph, const CaseTable& table, RowFormat format)
    : graph_(graph), table_(table), input_units_(table.shown_units()), format_(format) {}

SweepRows::Column SweepRows::column(std::size_t output, std::optional<std::size_t> element) const {
  Column c{output, element};
  const RequestedOutput& o = graph_.outputs[output];
  if (!o.spec->display_unit.empty()) {
    const UnitScale u = parse_unit(o.spec->display_unit);
    c.scale = u.scale;
    c.offset = u.offset;
  }
  return c;
}

std::vector<std::string> SweepRows::output_headers(const CaseResult* success, std::vector<Column>& columns) const {
  std::vector<std::string> names;
  for (std::size_t j = 0; j < graph_.outputs.size(); ++j) {
    const RequestedOutput& o = graph_.outputs[j];
    if (o.spec->kind == ValueKind::scalar) {
      names.push_back(sweep_column_name(graph_, j));
      columns.push_back(column(j, std::nullopt));
    } else if (o.spec->kind == ValueKind::series && success) {
      const Series& s = success->outputs[j].as_series();
      for (std::size_t e = 0; e < s.values.size(); ++e) {
        const std::string element = e < s.labels.size() ? s.labels[e] : std::to_string(e);
        names.push_back(with_unit(o.label + "[" + element + "]", unit_of(graph_, o)));
        columns.push_back(column(j, e));
      }
    }
  }
  return names;
}

void SweepRows::settle(const CaseResult* success) {
  if (settled_) return;
  header_ = {"case"};
  const std::vector<std::string> inputs = input_headers();
  header_.insert(header_.end(), inputs.begin(), inputs.end());
  std::vector<std::string> outputs = output_headers(success, columns_);
  std::vector<std::string> taken = reserved_columns;
  taken.insert(taken.end(), inputs.begin(), inputs.end());
  make_unique(outputs, taken, "out.");
  header_.insert(header_.end(), outputs.begin(), outputs.end());
  header_.push_back("exit");
  header_.push_back("error");
  settled_ = true;
}

void SweepRows::adopt(const std::vector<std::string>& header) {
  // The file's header must be what this sweep would write: the series columns tell their length.
  std::vector<Column> columns;
  // Compared as a reader gets the cells back (csv_text: what csv_field wrote, unquoted).
  std::vector<std::string> expected = {"case"};
  for (const std::string& name : input_headers()) expected.push_back(csv_text(name));
  const std::size_t fixed = expected.size();
  if (header.size() < fixed + 2 || !std::equal(expected.begin(), expected.end(), header.begin()) ||
      header[header.size() - 2] != "exit" || header.back() != "error")
    throw UsageError("the file being resumed has other columns than this sweep writes (" + excerpt(csv_row(header)) + ")");
  // An output column may carry "out." prefixes (make_unique); they name the same output.
  auto bare = [](std::string_view name) {
    while (name.rfind("out.", 0) == 0) name.remove_prefix(4);
    return std::string(name);
  };
  for (std::size_t j = 0, h = fixed; j < graph_.outputs.size(); ++j) {
    const RequestedOutput& o = graph_.outputs[j];
    if (o.spec->kind == ValueKind::scalar) {
      if (h >= header.size() - 2 || bare(header[h]) != csv_text(sweep_column_name(graph_, j)))
        throw UsageError("the file being resumed has no column for '" + o.label + "' where this sweep writes it");
      columns.push_back(column(j, std::nullopt));
      ++h;
    } else if (o.spec->kind == ValueKind::series) {
      for (std::size_t e = 0; h < header.size() - 2 && bare(header[h]).rfind(o.label + "[", 0) == 0; ++e, ++h) columns.push_back(column(j, e));
    }
  }
  if (fixed + columns.size() + 2 != header.size())
    throw UsageError("the file being resumed has columns this sweep does not write");
  if (std::set<std::string>(header.begin(), header.end()).size() != header.size())
    throw UsageError("the file being resumed names a column twice; it is not a sweep's");
  header_ = header;
  columns_ = std::move(columns);
  settled_ = true;
}

std::string SweepRows::format(const std::vector<std::string>& cells, const std::vector<bool>& numeric) const {
  if (format_ == RowFormat::csv) return csv_row(cells) + "\n";
  std::ostringstream os;
  JsonWriter json(os);
  json.begin_object();
  for (std::size_t c = 0; c < cells.size(); ++c) {
    json.key(header_[c]);
    if (cells[c].empty()) json.null();
    else if (c == 0 || c + 2 == cells.size()) json.value(std::strtol(cells[c].c_str(), nullptr, 10));  // case, exit
    // Shortest round-trip text: the same double. A cell that is not a finite number (a value
    // shown as written) goes as text: JSON has no inf or NaN, and one case must not end the sweep.
    else if (const std::optional<double> x = numeric[c] ? finite_number_in_cell(cells[c]) : std::nullopt) json.value(*x);
    else json.value(cells[c]);
  }
  json.end_object();
  return os.str() + "\n";
}

void RowSequencer::settle(const CaseResult* success) {
  rows_.settle(success);
  header_fixed_();
  for (const CaseResult& r : waiting_) row_(r);
  waiting_.clear();
}

void RowSequencer::operator()(CaseResult&& result) {
  if (!rows_.settled()) {
    if (result.failure != CaseFailure::none) {
      waiting_.push_back(std::move(result));
      return;
    }
    settle(&result);
  }
  row_(result);
}

void RowSequencer::finish() {
  if (!rows_.settled()) settle(nullptr);
}

std::string SweepRows::shape_problem(const CaseResult& result) const {
  // A series must have as many elements as the header gave it columns (fixed by the first success).
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (!columns_[c].element) continue;
    const std::size_t j = columns_[c].output;
    const bool last_of_series = c + 1 == columns_.size() || columns_[c + 1].output != j;
    const std::size_t have = result.outputs[j].as_series().values.size();
    if (have <= *columns_[c].element)
      return "output '" + graph_.outputs[j].label + "' has " + std::to_string(have) +
             " elements in this case, fewer than the sweep's columns";
    if (last_of_series && have != *columns_[c].element + 1)
      return "output '" + graph_.outputs[j].label + "' has " + std::to_string(have) + " elements in this case, the sweep's columns have " +
             std::to_string(*columns_[c].element + 1);
  }
  return {};
}

double SweepRows::cell_value(const CaseResult& result, const Column& c) const {
  const Value& value = result.outputs[c.output];
  return shown(c.element ? value.as_series().values[*c.element] : value.as_scalar(), c);
}

void SweepRows::append_line(std::string& out, const CaseResult& result, int exit_code) const {
  if (format_ != RowFormat::csv) {
    out += line(result, exit_code);
    return;
  }
  // The same cells as line(), written straight into `out`: numbers by std::to_chars, every cell
  // through append_csv_field, no string per cell.
  std::string error = result.failure == CaseFailure::none ? shape_problem(result) : result.error;
  if (result.failure == CaseFailure::none && !error.empty()) exit_code = evaluation_error;
  // A number as to_chars writes it is a cell append_csv_field leaves as it is (digits, '.', 'e',
  // a leading '-' that reads as a number): appended straight.
  char buffer[32];
  auto number = [&](auto x) {
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
    const std::string_view text(buffer, static_cast<std::size_t>(end - buffer));
    if constexpr (std::is_floating_point_v<decltype(x)>) {
      if (!std::isfinite(x)) return append_csv_field(out, text);  // never met: outputs are finite
    }
    out.append(text);
  };
  number(result.index);
  thread_local std::string input;
  for (std::size_t v = 0; v < table_.variables.size(); ++v) {
    out += ',';
    // A number's digits go straight into the row (append_csv_field leaves them as they are);
    // text as written goes through it.
    const std::size_t mark = out.size();
    if (table_.append_shown(out, result.index, v, input_units_[v])) continue;
    input.assign(out, mark);
    out.resize(mark);
    append_csv_field(out, input);
  }
  const bool values = result.failure == CaseFailure::none && error.empty();
  for (const Column& c : columns_) {
    out += ',';
    if (values) number(cell_value(result, c));
  }
  out += ',';
  number(exit_code);
  out += ',';
  append_csv_field(out, error);
  out += '\n';
}

std::string SweepRows::line(const CaseResult& result, int exit_code) const {
  if (format_ == RowFormat::csv) {
    std::string out;
    append_line(out, result, exit_code);
    return out;
  }
  std::vector<std::string> cells = {std::to_string(result.index)};
  std::vector<bool> numeric = {true};
  CaseValue made;
  for (std::size_t v = 0; v < table_.variables.size(); ++v) {
    cells.push_back(table_.shown(result.index, v));
    numeric.push_back(table_.number_cell(result.index, v, made).si.has_value());
  }
  std::string error = result.failure == CaseFailure::none ? shape_problem(result) : result.error;
  if (result.failure == CaseFailure::none && !error.empty()) exit_code = evaluation_error;
  const bool values = result.failure == CaseFailure::none && error.empty();
  for (const Column& c : columns_) {
    cells.push_back(values ? exact(cell_value(result, c)) : std::string());
    numeric.push_back(true);
  }
  cells.push_back(std::to_string(exit_code));
  numeric.push_back(true);
  cells.push_back(error);
  numeric.push_back(false);
  return format(cells, numeric);
}

std::variant<std::monostate, double, std::string> SweepRows::input_value(std::size_t i, std::size_t v, std::string& cell) const {
  cell.clear();
  const double number = input_number(i, v, cell);  // a number only where the cell shows one
  if (!std::isnan(number)) return number;
  if (cell.empty()) return std::monostate{};
  return cell;
}

double SweepRows::input_number(std::size_t i, std::size_t v, std::string& cell) const {
  // A number given as a double and shown as its digits: the number itself, which they read back to.
  if (const double given = table_.shown_given_number(i, v, input_units_[v]); !std::isnan(given)) return given;
  // The cell as a row shows it (the column's unit parsed once), read back where it is a number.
  cell.clear();
  table_.append_shown(cell, i, v, input_units_[v]);
  CaseValue made;
  if (cell.empty() || !table_.number_cell(i, v, made).si.has_value()) return std::numeric_limits<double>::quiet_NaN();
  return finite_number_in_cell(cell).value_or(std::numeric_limits<double>::quiet_NaN());
}

int SweepRows::outcome(const CaseResult& result, int exit_code, std::vector<double>& outputs, std::string& error) const {
  error = result.failure == CaseFailure::none ? shape_problem(result) : result.error;
  if (result.failure != CaseFailure::none || !error.empty()) return result.failure == CaseFailure::none ? evaluation_error : exit_code;
  for (const Column& c : columns_) outputs.push_back(cell_value(result, c));
  return exit_code;
}

}  // namespace mechgraph::host

namespace mechgraph::host {

ForeignLineMarks strip_foreign_line_marks(std::string& line, std::size_t number) {
  ForeignLineMarks found;
  constexpr std::string_view mark = "\xEF\xBB\xBF";
  if (number == 1 && std::string_view(line).starts_with(mark)) {
    line.erase(0, mark.size());
    found.byte_order_mark = true;
  }
  if (!line.empty() && line.back() == '\r') {
    line.pop_back();
    found.carriage_return = true;
  }
  return found;
}

std::string foreign_line_marks_text(const ForeignLineMarks& marks) {
  std::string text;
  if (marks.byte_order_mark) text = "starts with a UTF-8 byte order mark";
  if (marks.carriage_return) text += std::string(text.empty() ? "" : " and ") + "ends in CR LF (a Windows line end)";
  return text + ", where mechgraph writes LF alone and no mark";
}

void RowChecker::refuse(std::size_t number, const std::string& why) const {
  throw UsageError(excerpt(file_) + ":" + std::to_string(number) + ": " + why +
                   "; refused: not a row mechgraph wrote for this sweep (edited or damaged?)");
}

void RowChecker::header(std::string_view line, std::size_t number) {
  try {
    header_ = split_csv_line(line);
  } catch (const std::invalid_argument& e) {
    refuse(number, std::string("the header: ") + e.what());
  }
  if (header_.size() < 3 || header_.front() != "case" || header_[header_.size() - 2] != "exit" || header_.back() != "error")
    refuse(number, "the header is not case,...,exit,error");
  if (std::set<std::string>(header_.begin(), header_.end()).size() != header_.size()) refuse(number, "the header names a column twice");
  if (rules_.inputs && header_.size() < 3 + *rules_.inputs) refuse(number, "the header has fewer columns than the sweep's inputs");
}

std::size_t RowChecker::case_number(std::string_view text, std::size_t number) {
  if (text.empty() || text.size() > 19 || !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
    refuse(number, "the case number '" + excerpt(text, 40) + "' is not a whole number");
  std::size_t index = 0;
  std::from_chars(text.data(), text.data() + text.size(), index);
  if (index >= rules_.cases) refuse(number, "case " + std::to_string(index) + " is not one of the sweep's " + std::to_string(rules_.cases));
  if (index % rules_.shards != rules_.shard)
    refuse(number, "case " + std::to_string(index) + " is not in shard " + std::to_string(rules_.shard) + "/" + std::to_string(rules_.shards));
  if (previous_ && index <= *previous_)
    refuse(number, "case " + std::to_string(index) + " after case " + std::to_string(*previous_) + " (out of order or written twice)");
  previous_ = index;
  return index;
}

void RowChecker::check_exit_and_outputs(const std::vector<std::string>& cells, const std::vector<bool>& plain, std::size_t number) const {
  const std::string& exit = cells[cells.size() - 2];
  if (exit != "0" && exit != "2" && exit != "3") refuse(number, "the exit '" + excerpt(exit, 40) + "' is not 0, 2 or 3");
  if (!rules_.inputs) return;
  std::size_t filled = 0, outputs = 0;
  for (std::size_t c = 1 + *rules_.inputs; c + 2 < cells.size(); ++c, ++outputs) {
    if (cells[c].empty()) continue;
    if (!plain[c] || !finite_number_cell(cells[c]))
      refuse(number, "column '" + excerpt(header_[c], 60) + "' holds '" + excerpt(cells[c], 40) + "', not a finite number");
    ++filled;
  }
  if (exit == "0" && (filled != outputs || !cells.back().empty())) refuse(number, "a success (exit 0) without all its values, or with an error");
  if (exit != "0" && filled != 0) refuse(number, "a failed case (exit " + exit + ") with values");
}

RowChecker::Row RowChecker::row(std::string_view line, std::size_t number) {
  std::vector<std::string> cells;
  std::vector<bool> plain;  // a JSON number or null, not a string
  if (rules_.format == RowFormat::csv) {
    try {
      cells = split_csv_line(line);
    } catch (const std::invalid_argument& e) {
      refuse(number, e.what());
    }
    if (cells.size() != header_.size())
      refuse(number, std::to_string(cells.size()) + " cells, the header has " + std::to_string(header_.size()));
    // Every cell as csv_field writes it: a formula-like cell mechgraph would have neutralised, or a
    // line break, was put there by someone else.
    for (const std::string& cell : cells)
      if (csv_text(cell) != cell) refuse(number, "the cell '" + excerpt(cell, 40) + "' is not as mechgraph writes cells");
    plain.assign(cells.size(), true);
  } else {
    std::vector<std::string> keys;
    if (!FlatJson(line).read(keys, cells, plain)) refuse(number, "not a flat JSON object as the rows are written");
    if (header_.empty()) {
      if (keys.size() < 3 || keys.front() != "case" || keys[keys.size() - 2] != "exit" || keys.back() != "error")
        refuse(number, "the keys are not case,...,exit,error");
      if (std::set<std::string>(keys.begin(), keys.end()).size() != keys.size()) refuse(number, "a key appears twice");
      if (rules_.inputs && keys.size() < 3 + *rules_.inputs) refuse(number, "fewer keys than the sweep's inputs");
      header_ = keys;
    } else if (keys != header_) {
      refuse(number, "other keys than the first row's");
    }
    if (!plain.front() || !plain[plain.size() - 2]) refuse(number, "the case or exit is not a number");
  }
  const std::size_t index = case_number(cells.front(), number);
  // --resume knows the cases: every row must carry the inputs of its case, as this sweep writes
  // them (CSV: the cell's text; JSON Lines: the same number, or the same text, or null for none).
  if (rules_.shown_input && rules_.inputs)
    for (std::size_t v = 0; v < *rules_.inputs && 1 + v < cells.size(); ++v) {
      const std::string expected = rules_.shown_input(index, v);
      const std::string& cell = cells[1 + v];
      bool same = false;
      if (rules_.format == RowFormat::csv) same = cell == csv_text(expected);
      else if (!plain[1 + v]) same = cell == expected;
      else if (cell.empty()) same = expected.empty();
      else {
        const std::optional<double> x = finite_number_in_cell(expected);
        same = x && finite_number_in_cell(cell) == x;
      }
      if (!same)
        refuse(number, "column '" + excerpt(header_[1 + v], 60) + "' holds '" + excerpt(cell, 40) + "', case " + std::to_string(index) +
                           " of this sweep has '" + excerpt(expected, 40) + "'");
    }
  check_exit_and_outputs(cells, plain, number);
  return {index, cells[cells.size() - 2] != "0"};
}

}  // namespace mechgraph::host
