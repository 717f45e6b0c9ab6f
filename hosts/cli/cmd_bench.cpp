// mechgraph bench SCENE: work-precision of every accuracy knob (error against a tight reference
// and the time it cost), as a table, JSON, or CSV + JSON files.
#include "cli.hpp"
#include "results_folder.hpp"
#include "spawn.hpp"
#include "options.hpp"

#include <mechgraph/csv.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/json_writer.hpp>
#include <mechgraph/knob_bench.hpp>
#include <mechgraph/text_escape.hpp>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace mechgraph::cli {
namespace {

void write_json(std::ostream& os, const std::vector<KnobTrial>& trials, const std::vector<KnobAdvice>& advice) {
  JsonWriter json(os);
  json.begin_object().key("advice").begin_array();
  for (const KnobAdvice& a : advice) {
    json.begin_object().key("node").value(a.node).key("knob").value(a.knob);
    json.key("recommended");
    if (a.recommended) json.value(trials[*a.recommended].setting);
    else json.null();
    json.key("default_off_front").value(a.current_off_front).key("text").value(a.text).end_object();
  }
  json.end_array();
  json.key("trials").begin_array();
  for (const KnobTrial& t : trials) {
    json.begin_object();
    json.key("node").value(t.node).key("type").value(t.type).key("knob").value(t.knob).key("setting").value(t.setting);
    json.key("default").value(t.is_default);
    if (t.failure.empty()) {
      json.key("seconds").value(t.seconds).key("max_relative_error").value(t.max_relative_error);
      json.key("worst_output").value(t.worst_output).key("on_front").value(t.on_front);
      json.key("errors").begin_object();
      for (const auto& [output, error] : t.errors) json.key(output).value(error);
      json.end_object();
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
  os << "node,type,knob,setting,default,on_front,seconds,max_relative_error,worst_output,work,failure\n";
  for (const KnobTrial& t : trials) {
    std::string work;
    for (const auto& [counter, amount] : t.work) work += (work.empty() ? "" : ";") + counter + "=" + std::to_string(amount);
    os << csv_row({t.node, t.type, t.knob, t.setting}) << "," << (t.is_default ? 1 : 0) << "," << (t.on_front ? 1 : 0) << ","
       << t.seconds << "," << t.max_relative_error << "," << csv_row({t.worst_output, work, t.failure}) << "\n";
  }
}

void write_table(std::ostream& os, const std::vector<KnobTrial>& trials, const std::vector<KnobAdvice>& advice) {
  std::string last;
  std::size_t group_index = 0;
  auto close_group = [&] {
    if (!last.empty() && group_index < advice.size()) os << "  -> " << advice[group_index++].text << "\n";
  };
  for (const KnobTrial& t : trials) {
    const std::string group = t.node + " (" + t.type + ") knob " + t.knob;
    if (group != last) {
      close_group();
      os << (last.empty() ? "" : "\n") << group << "\n";
      os << "  setting                     time [s]   max rel. error   work\n";
      last = group;
    }
    char line[200];
    if (!t.failure.empty()) {
      std::snprintf(line, sizeof line, "  %-22s %s    failed: ", t.setting.c_str(), t.is_default ? "*" : " ");
      os << line << t.failure << "\n";
      continue;
    }
    std::string work;
    for (const auto& [counter, amount] : t.work) {
      char w[64];
      std::snprintf(w, sizeof w, "%s%s=%.0f", work.empty() ? "" : " ", counter.c_str(), amount);
      work += w;
    }
    std::snprintf(line, sizeof line, "  %-22s %s%s %10.3g   %14.3g   ", t.setting.c_str(), t.is_default ? "*" : " ",
                  t.on_front ? "P" : " ", t.seconds, t.max_relative_error);
    os << line << work << "\n";
  }
  close_group();
  os << "\n* the scene's setting; P on the Pareto front (no other setting both faster and more accurate);\n"
        "  error against every numeric knob tightened past the ladder (Monte Carlo: 2^(steps+2) times the samples)\n";
}

// The work-precision plot: log error over log time, one line per node and knob, drawn by gnuplot
// (Debian's gnuplot-nox) as SVG. Errors of exactly zero sit at 1e-17, below double precision.
void write_plot(const std::filesystem::path& dir, const std::vector<KnobTrial>& trials) {
  std::ofstream data(dir / "bench.dat");
  std::vector<std::string> titles;
  std::string last;
  for (const KnobTrial& t : trials) {
    if (!t.failure.empty() || !(t.seconds > 0)) continue;
    const std::string group = t.node + "." + t.knob;
    if (group != last) {
      if (!last.empty()) data << "\n\n";
      titles.push_back(group);
      last = group;
    }
    data << t.seconds << " " << std::max(t.max_relative_error, 1e-17) << " " << (t.is_default ? 1 : 0) << "\n";
  }
  data.close();
  check_written(data, dir / "bench.dat");
  std::ofstream script(dir / "bench.gp");
  script << "set terminal svg size 900,600 dynamic enhanced font 'sans,11'\n"
         << "set output 'bench.svg'\n"
         << "set logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
         << "set xlabel 'time of the node [s]'\nset ylabel 'max. relative error'\n"
         << "set title 'Work-precision of the accuracy knobs (filled: the scene setting)'\n"
         << "set key outside right\nset grid\n"
         << "plot";
  for (std::size_t i = 0; i < titles.size(); ++i)
    script << (i ? ", \\\n    " : " ") << "'bench.dat' index " << i << " using 1:2 with linespoints lc " << i + 1
           << " pt 6 title " << gnuplot_string(titles[i]) << " noenhanced, '' index " << i << " using 1:($3 > 0 ? $2 : 1/0) with points lc " << i + 1
           << " pt 7 ps 1.5 notitle";
  script << "\n";
  script.close();
  if (!script) throw IoError("cannot write '" + (dir / "bench.gp").string() + "'");
  const std::optional<std::filesystem::path> gnuplot = find_program("gnuplot");
  if (!gnuplot) {
    spdlog::warn("bench: gnuplot is not installed (apt-get install gnuplot-nox): no bench.svg, its data is in bench.dat");
    return;
  }
  // From an argument vector in the results folder: no shell reads the folder's name.
  const SpawnOutcome run = run_program(*gnuplot, {"bench.gp"}, dir, dir / "gnuplot.log", std::chrono::minutes(2));
  if (!run.succeeded()) spdlog::warn("bench: gnuplot failed ({}); bench.gp, bench.dat and gnuplot.log are in the folder", run.describe());
  else std::filesystem::remove(dir / "gnuplot.log");
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
      "force", "replace the results in an existing --out DIR")(
      "tol", po::value<double>()->default_value(1e-9), "recommend the cheapest setting within this relative error");
  po::variables_map vm;
  if (!parse_scene_command(args, visible, vm, "mechgraph bench SCENE [--node NAME] [--steps N] [--tol 1e-9] [--json] [--out DIR]"))
    return ok;
  KnobBenchOptions options;
  if (vm.count("node")) options.node = vm["node"].as<std::string>();
  options.steps = vm["steps"].as<int>();
  options.repeats = vm["repeats"].as<int>();
  if (options.steps < 0 || options.steps > 20) throw UsageError("--steps must be between 0 and 20");
  if (options.repeats < 1 || options.repeats > 100) throw UsageError("--repeats must be between 1 and 100");
  if (vm.count("out")) check_results_folder(vm["out"].as<std::string>(), vm.count("force") > 0);
  const PluginRegistry registry = load_plugins(g);
  const Graph graph = load_scene_graph(vm, registry);
  // The bench evaluates far more than the scene: a reference with every knob 2^(steps+2) times
  // tighter, then 2 steps + 1 settings of each knob, each `repeats` times. Its work is checked as
  // that many evaluations of the scene (an upper bound: a looser setting costs less).
  std::size_t knobs = 0;
  for (std::size_t i : graph.order)
    for (const ParamSpec& p : graph.nodes[i].info().params) knobs += p.knob ? 1 : 0;
  const double evaluations = std::ldexp(1.0, options.steps + 2) +
                             static_cast<double>((2 * options.steps + 1) * options.repeats) * static_cast<double>(std::max<std::size_t>(knobs, 1));
  check_work_budget(graph, estimate_work(graph), work_budget(vm), evaluations, false);
  const double tolerance = vm["tol"].as<double>();
  if (!(tolerance > 0.0)) throw UsageError("--tol must be > 0");
  options.progress = [](std::size_t done, std::size_t total, const std::string& node) {
    spdlog::info("bench: node {} of {}: {}", done + 1, total, node);
  };
  std::vector<KnobTrial> trials = bench_knobs(graph, options);
  const std::vector<KnobAdvice> advice = advise_knobs(trials, tolerance);
  spdlog::info("{} knob settings measured", trials.size());
  // Built whole first: an error while writing leaves stdout empty, not a truncated document.
  std::ostringstream shown;
  if (vm.count("json")) write_json(shown, trials, advice);
  else write_table(shown, trials, advice);
  std::cout << shown.str();
  if (vm.count("out")) {
    const std::filesystem::path dir = vm["out"].as<std::string>();
    write_results_folder(dir, vm.count("force") > 0, [&](const std::filesystem::path& staging) {
      std::ofstream csv(staging / "bench.csv"), json(staging / "bench.json");
      if (!csv || !json) throw IoError("cannot write into '" + staging.string() + "'");
      write_csv(csv, trials);
      write_json(json, trials, advice);
      csv.close();
      json.close();
      check_written(csv, dir / "bench.csv");
      check_written(json, dir / "bench.json");
      write_plot(staging, trials);
    });
  }
  return ok;
}

}  // namespace mechgraph::cli
