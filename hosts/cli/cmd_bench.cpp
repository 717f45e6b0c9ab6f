// mechgraph bench SCENE: work-precision of every accuracy knob (error against a tight reference
// and the time it cost), as a table, JSON, or CSV + JSON files.
#include "cli.hpp"
#include "results_folder.hpp"
#include "options.hpp"

#include <mechgraph/json_writer.hpp>
#include <mechgraph/knob_bench.hpp>

#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace mechgraph::cli {
namespace {

void write_json(std::ostream& os, const std::vector<KnobTrial>& trials) {
  JsonWriter json(os);
  json.begin_object().key("trials").begin_array();
  for (const KnobTrial& t : trials) {
    json.begin_object();
    json.key("node").value(t.node).key("type").value(t.type).key("knob").value(t.knob).key("setting").value(t.setting);
    json.key("default").value(t.is_default);
    if (t.failure.empty()) {
      json.key("seconds").value(t.seconds).key("max_relative_error").value(t.max_relative_error);
      json.key("worst_output").value(t.worst_output);
      json.key("work").begin_object();
      for (const auto& [counter, amount] : t.work) json.key(counter).value(amount);
      json.end_object();
    } else {
      json.key("failure").value(t.failure);
    }
    json.end_object();
  }
  json.end_array().end_object();
  os << "\n";
}

void write_csv(std::ostream& os, const std::vector<KnobTrial>& trials) {
  os << "node,type,knob,setting,default,seconds,max_relative_error,worst_output,work,failure\n";
  for (const KnobTrial& t : trials) {
    std::string work;
    for (const auto& [counter, amount] : t.work) work += (work.empty() ? "" : ";") + counter + "=" + std::to_string(amount);
    os << t.node << "," << t.type << "," << t.knob << ",\"" << t.setting << "\"," << (t.is_default ? 1 : 0) << ","
       << t.seconds << "," << t.max_relative_error << "," << t.worst_output << "," << work << ",\"" << t.failure << "\"\n";
  }
}

void write_table(std::ostream& os, const std::vector<KnobTrial>& trials) {
  std::string last;
  for (const KnobTrial& t : trials) {
    const std::string group = t.node + " (" + t.type + ") knob " + t.knob;
    if (group != last) {
      os << (last.empty() ? "" : "\n") << group << "\n";
      os << "  setting                   time [s]   max rel. error   work\n";
      last = group;
    }
    char line[160];
    if (!t.failure.empty()) {
      std::snprintf(line, sizeof line, "  %-22s %s  failed: ", t.setting.c_str(), t.is_default ? "*" : " ");
      os << line << t.failure << "\n";
      continue;
    }
    std::string work;
    for (const auto& [counter, amount] : t.work) {
      char w[64];
      std::snprintf(w, sizeof w, "%s%s=%.0f", work.empty() ? "" : " ", counter.c_str(), amount);
      work += w;
    }
    std::snprintf(line, sizeof line, "  %-22s %s %10.3g   %14.3g   ", t.setting.c_str(), t.is_default ? "*" : " ", t.seconds,
                  t.max_relative_error);
    os << line << work << "\n";
  }
  os << "\n* the scene's setting; error against every numeric knob tightened past the ladder\n";
}

}  // namespace

int bench_command(const GlobalOptions& g, const std::vector<std::string>& args) {
  po::options_description visible("bench options");
  add_scene_options(visible);
  visible.add_options()(
      "node", po::value<std::string>(), "only this node")("steps", po::value<int>()->default_value(3),
                                                          "ladder: each knob from x 2^-steps to x 2^steps")(
      "repeats", po::value<int>()->default_value(3), "time = fastest of this many evaluations")(
      "json", "print JSON on stdout")("out", po::value<std::string>(),
                                       "also write bench.csv and bench.json into DIR (whole or not at all)")(
      "force", "replace the results in an existing --out DIR");
  po::variables_map vm;
  if (!parse_scene_command(args, visible, vm, "mechgraph bench SCENE [--node NAME] [--steps N] [--json] [--out DIR]"))
    return ok;
  KnobBenchOptions options;
  if (vm.count("node")) options.node = vm["node"].as<std::string>();
  options.steps = vm["steps"].as<int>();
  options.repeats = vm["repeats"].as<int>();
  if (options.steps < 0 || options.steps > 20) throw UsageError("--steps must be between 0 and 20");
  if (options.repeats < 1) throw UsageError("--repeats must be at least 1");
  if (vm.count("out")) check_results_folder(vm["out"].as<std::string>(), vm.count("force") > 0);
  const PluginRegistry registry = load_plugins(g);
  const Graph graph = load_scene_graph(vm, registry);
  const std::vector<KnobTrial> trials = bench_knobs(graph, options);
  spdlog::info("{} knob settings measured", trials.size());
  if (vm.count("json")) write_json(std::cout, trials);
  else write_table(std::cout, trials);
  if (vm.count("out")) {
    const std::filesystem::path dir = vm["out"].as<std::string>();
    write_results_folder(dir, vm.count("force") > 0, [&](const std::filesystem::path& staging) {
      std::ofstream csv(staging / "bench.csv"), json(staging / "bench.json");
      if (!csv || !json) throw IoError("cannot write into '" + staging.string() + "'");
      write_csv(csv, trials);
      write_json(json, trials);
      csv.close();
      json.close();
      check_written(csv, dir / "bench.csv");
      check_written(json, dir / "bench.json");
    });
  }
  return ok;
}

}  // namespace mechgraph::cli
