// mechgraph report SCENE [--set NAME=VALUE ...] [--out DIR] [--force] [--threads N] [--pdf]
#include "cli.hpp"
#include <mechgraph/host/terminal_output.hpp>
#include "options.hpp"
#include "report_page.hpp"
#include "report_pdf.hpp"
#include "results_folder.hpp"

#include <mechgraph/evaluator.hpp>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <iostream>
#include <thread>

namespace mechgraph::cli {
namespace {

// The scene as written plus, as outputs, every table and series output of every node (the curves
// and shares a report plots; what they mark is in their data), leaving out those of an effect the
// node does not run with. Only the nodes the scene itself needs (`needed`, from its outputs and
// report tables; every node when it asks for nothing) are drawn: a node the scene culls
// (culling_demo.yaml's refused design) stays culled.
SceneSpec with_every_curve(SceneSpec scene, const PluginRegistry& registry, const std::vector<std::string>& needed) {
  std::vector<std::string> scene_effects;
  for (const auto& [name, where] : scene.effects) scene_effects.push_back(name);
  for (const NodeSpec& n : scene.nodes) {
    if (std::find(needed.begin(), needed.end(), n.name) == needed.end()) continue;
    const RegisteredType* type = registry.find(n.type);
    if (!type) continue;  // build_graph names it
    const NodeInfo& info = type->type->info();
    for (const PortSpec& port : info.outputs) {
      if (port.kind != ValueKind::table && port.kind != ValueKind::series) continue;
      if (const EffectSpec* e = info.effect_of_output(port.name)) {
        const bool on = std::find(scene_effects.begin(), scene_effects.end(), e->name) != scene_effects.end() ||
                        std::any_of(n.effects.begin(), n.effects.end(), [&](const auto& ne) { return ne.first == e->name; });
        if (!on) continue;
      }
      // An output made only with inputs this node is not given (a deviation from a
      // master law) is not there to draw.
      if (const auto deps = info.output_dependencies.find(port.name); deps != info.output_dependencies.end()) {
        const bool given = std::all_of(deps->second.begin(), deps->second.end(), [&](const std::string& in) {
          return std::any_of(n.inputs.begin(), n.inputs.end(), [&](const NodeSpec::InputSpec& i) { return i.port == in; });
        });
        if (!given) continue;
      }
      const bool listed = std::any_of(scene.outputs.begin(), scene.outputs.end(),
                                      [&](const PortRef& r) { return r.node == n.name && r.port == port.name; });
      if (!listed) scene.outputs.push_back(PortRef{n.name, port.name, n.where});
    }
  }
  return scene;
}

}  // namespace

int report_command(const GlobalOptions& g, const std::vector<std::string>& args) {
  po::options_description visible("report options");
  add_scene_options(visible);
  visible.add_options()("out", po::value<std::string>()->default_value("report"),
                        "write report.html, results.json and the CSV of every plot and table into DIR "
                        "(whole or not at all; a report this command wrote there before is replaced, any other "
                        "existing DIR needs --force)")(
      "force", "replace other results mechgraph wrote in an existing --out DIR")(
      "pdf", "also print the page to report.pdf with Debian's headless chromium (file:// only, no network)")(
      "threads", po::value<unsigned>()->default_value(1), "evaluate independent nodes on this many threads (0: one per core)");
  po::variables_map vm;
  if (!parse_scene_command(args, visible, vm, "mechgraph report SCENE [--set NAME=VALUE ...] [--out DIR] [--force] [--threads N] [--pdf]"))
    return ok;
  const std::filesystem::path dir = vm["out"].as<std::string>();
  // Running the same report again regenerates it: its own folder (mechgraph's marker and a
  // report.html) is replaced without --force; anything else as for every results folder.
  const bool replace = vm.count("force") > 0 || is_own_results_folder(dir, "report.html");
  check_results_folder(dir, replace);
  if (vm.count("pdf")) require_pdf_printer();
  const PluginRegistry registry = load_plugins(g);
  const RunInputs inputs{vm["scene"].as<std::string>(),
                         vm.count("set") ? vm["set"].as<std::vector<std::string>>() : std::vector<std::string>{}};
  std::vector<Override> overrides;
  for (const std::string& s : inputs.overrides) overrides.push_back(parse_override(s));
  const SceneSpec scene = load_scene(inputs.scene_file);
  // A scene that asks for nothing (no outputs, no report) is drawn whole.
  std::vector<std::string> needed;
  if (scene.outputs.empty() && scene.report.empty()) {
    for (const NodeSpec& n : scene.nodes) needed.push_back(n.name);
  } else {
    for (const GraphNode& n : build_graph(scene, registry, overrides).nodes)
      if (n.needed) needed.push_back(n.name);
  }
  const Graph graph = build_graph(with_every_curve(scene, registry, needed), registry, overrides);
  check_work_budget(graph, estimate_work(graph), work_budget(vm), 1, true);
  unsigned threads = vm["threads"].as<unsigned>();
  if (threads > max_threads) throw UsageError("--threads " + std::to_string(threads) + " is more than " + std::to_string(max_threads));
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  MemoCache cache;
  const RunResult result = evaluate(graph, cache, threads);
  write_results_folder(dir, replace, [&](const std::filesystem::path& staging) {
    write_report_page(staging, graph, result, registry, inputs);
    if (vm.count("pdf")) print_report_pdf(staging);
  });
  // The user's folder name: through terminal_text.
  print_text((dir / "report.html").string() + "\n");
  if (vm.count("pdf")) print_text((dir / "report.pdf").string() + "\n");
  spdlog::info("report written to {}{}", (dir / "report.html").string(),
               vm.count("pdf") ? " and " + (dir / "report.pdf").string() : std::string());
  return ok;
}

}  // namespace mechgraph::cli
