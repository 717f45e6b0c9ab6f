// mechgraph run SCENE [--set NAME=VALUE ...] [--json] [--out DIR]
#include "cli.hpp"
#include "options.hpp"
#include "result_files.hpp"
#include "results_folder.hpp"
#include <mechgraph/host/terminal_output.hpp>

#include <mechgraph/errors.hpp>
#include <mechgraph/evaluator.hpp>
#include <mechgraph/json_writer.hpp>
#include <mechgraph/text_escape.hpp>
#include <mechgraph/shown_number.hpp>
#include <mechgraph/units.hpp>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <thread>

namespace mechgraph::cli {
namespace {

// A node makes the notes it declares (NodeInfo::notes) while it computes their output when their
// parameter is given; run prints notes, so that output is wanted of every such node, whether or not
// the scene lists it.
void want_declared_notes(Graph& graph) {
  for (GraphNode& n : graph.nodes) {
    if (!n.needed) continue;
    for (const NoteDecl& note : n.info().notes) {
      if (!n.params.has(note.when_param) || !n.info().find_output(note.output)) continue;
      if (std::find(n.wanted.begin(), n.wanted.end(), note.output) != n.wanted.end()) continue;
      n.wanted.insert(std::upper_bound(n.wanted.begin(), n.wanted.end(), note.output), note.output);
      refresh_wanted_mask(n);
    }
  }
}

}  // namespace

namespace {

// A table short enough to read on the terminal (an events table) is printed row by row, each
// column in its display unit; longer ones (curves) go to the CSV files of --out.
constexpr std::size_t printed_table_rows = 40;

// A channel with declared codes shows each row's name beside the number ("1 contact_lost").
// A unit of degrees says which angle its column counts, as the column declares it ("[deg (shaft)]").
void print_short_table(std::ostream& os, const Table& t, const DeclaredPort& declared) {
  std::vector<const Table::Column*> columns{&t.axis};
  for (const Table::Column& c : t.channels) columns.push_back(&c);
  const auto unit_of = [](const Table::Column& c) {
    if (!c.display_unit.empty()) return c.display_unit;
    const std::string si = c.dimension.si_unit();
    return si == "1" ? std::string() : si;
  };
  // Every cell first, so that a column is as wide as its widest cell (a code's name).
  std::vector<std::vector<std::string>> cells(t.axis.values.size(), std::vector<std::string>(columns.size()));
  std::vector<std::size_t> width;
  std::vector<std::string> head;
  for (std::size_t k = 0; k < columns.size(); ++k) {
    const Table::Column& c = *columns[k];
    const std::string unit = unit_of(c);
    const std::string tagged = unit_with_reference(unit, declared.column_tag(c));
    head.push_back(terminal_text(c.name, TerminalLines::one) + (tagged.empty() ? "" : " [" + terminal_text(tagged, TerminalLines::one) + "]"));
    width.push_back(std::max<std::size_t>(head.back().size(), 12));
    const ChannelDecl* decl = declared.channel(c.name);
    const double floor = noise_floor(c.dimension, table_largest(t, c.dimension));
    for (std::size_t j = 0; j < t.axis.values.size(); ++j) {
      const double shown = c.display_unit.empty() ? c.values[j] : to_unit(c.values[j], c.dimension, c.display_unit);
      const std::string cell = shown_number(shown, c.values[j], floor);
      const std::string_view name = decl ? decl->code_name(c.values[j]) : std::string_view();
      cells[j][k] = name.empty() ? cell : cell + " " + terminal_text(name, TerminalLines::one);
      width[k] = std::max(width[k], cells[j][k].size());
    }
  }
  auto print_row = [&](const std::vector<std::string>& row) {
    for (std::size_t k = 0; k < row.size(); ++k) os << (k ? "  " : "    ") << std::setw(static_cast<int>(width[k])) << row[k];
    os << "\n";
  };
  print_row(head);
  for (const auto& row : cells) print_row(row);
}

}  // namespace

int run_command(const GlobalOptions& g, const std::vector<std::string>& args) {
  po::options_description visible("run options");
  add_scene_options(visible);
  visible.add_options()(
      "json", "print one JSON object on stdout")(
      "threads", po::value<unsigned>()->default_value(1),
      "evaluate independent nodes on this many threads (0: one per core)")("out", po::value<std::string>(),
                                                 "also write results.json and one CSV per series output into DIR "
                                                 "(written whole or not at all; an existing DIR needs --force)")(
      "force", "replace the results in an existing --out DIR");
  po::variables_map vm;
  if (!parse_scene_command(args, visible, vm,
                           "mechgraph run SCENE [--set NAME=VALUE ...] [--json] [--threads N] [--out DIR]"))
    return ok;

  if (vm.count("out")) check_results_folder(vm["out"].as<std::string>(), vm.count("force") > 0);
  const SceneSpec scene = load_scene(vm["scene"].as<std::string>());
  const PluginRegistry registry = plugins_for_scene(g, scene);
  // --json prints every requested curve on standard output: the same bound as --out's files.
  Graph graph = load_scene_graph(vm, scene, registry, vm.count("json") > 0);
  want_declared_notes(graph);
  MemoCache cache;
  unsigned threads = vm["threads"].as<unsigned>();
  if (threads > max_threads) throw UsageError("--threads " + std::to_string(threads) + " is more than " + std::to_string(max_threads));
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  const RunResult result = evaluate(graph, cache, threads);
  std::size_t evaluated = 0;
  for (const NodeRun& r : result.runs) evaluated += r.reused ? 0 : 1;
  spdlog::info("evaluated {} of {} nodes ({} reused from an identical node, {} culled)", evaluated, graph.nodes.size(),
               result.runs.size() - evaluated, graph.nodes.size() - graph.order.size());

  const RunInputs inputs{vm["scene"].as<std::string>(),
                         vm.count("set") ? vm["set"].as<std::vector<std::string>>() : std::vector<std::string>{}};
  if (vm.count("json")) {
    // Built whole first: an error while writing (a value JSON cannot hold) leaves stdout empty,
    // not a truncated object.
    std::ostringstream json;
    write_json(json, graph, result, registry, inputs);
    std::cout << json.str();
  } else {
    // Built whole, then shown through terminal_text (print_text): labels, names and notes are the
    // scene's and the plugins' text.
    std::ostringstream text;
    for (std::size_t t = 0; t < graph.reports.size(); ++t) {
      if (t) text << "\n";
      print_report(text, graph.reports[t], result, graph);
    }
    if (!graph.reports.empty() && graph.scene_output_count) text << "\n";
    if (graph.reports.empty() && !graph.title.empty()) {
      text << terminal_text(graph.title) << "\n\n";
    }
    for (std::size_t i = 0; i < graph.scene_output_count; ++i) {
      const OutputValue& o = result.outputs[i];
      text << terminal_text(o.label, TerminalLines::one) << " = ";
      if (o.value.kind() == ValueKind::scalar) {
        // The reader's unit when neither the scene nor the port names one (mm/deg^2, not m/rad^2),
        // and which angle a unit of degrees counts.
        const std::string unit = o.display_unit.empty() ? reader_unit(o.dimension) : o.display_unit;
        const PortSpec* spec = graph.outputs[i].spec;
        const std::string reference = spec ? angle_reference(graph.nodes[graph.outputs[i].node].info(), *spec) : std::string();
        text << format_value(o.value.as_scalar(), o.dimension, unit)
             << (unit.find("deg") != std::string::npos && !reference.empty() ? " (" + reference + ")" : std::string());
      }
      else if (o.value.kind() == ValueKind::series) print_series(text, o);
      else if (o.value.kind() == ValueKind::table) {
        text << "table of " << o.value.as_table().channels.size() << " curves over " << o.value.as_table().axis.values.size()
             << " points (see --out for the CSV)";
        const std::size_t rows = o.value.as_table().axis.values.size();
        if (rows > 0 && rows <= printed_table_rows) {
          text << "\n";
          print_short_table(text, o.value.as_table(), declared_port(graph, o.label));
          continue;
        }
      }
      else text << "<" << o.value.as_handle()->kind() << ">";
      text << "\n";
    }
    // How results were made (Monte Carlo samples and seed, ...), under everything they belong to.
    bool first_note = true;
    for (const NodeRun& r : result.runs)
      for (const std::string& n : r.notes) {
        if (first_note) text << "\n";
        first_note = false;
        text << r.node << ": " << terminal_text(n) << "\n";
      }
    print_text(text.str());
  }
  if (vm.count("out")) {
    const std::filesystem::path dir = vm["out"].as<std::string>();
    write_results_folder(dir, vm.count("force") > 0, [&](const std::filesystem::path& staging) {
      write_result_files(staging, graph, result, registry, inputs);
    });
    spdlog::info("results written to {}", dir.string());
  }
  return ok;
}

}  // namespace mechgraph::cli
