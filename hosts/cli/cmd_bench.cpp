// mechgraph bench SCENE: work-precision of every accuracy knob (each setting's error against the
// knob's own converged reference, or its spread over seeds for a Monte Carlo node, and the time it
// cost), as a table, JSON, or CSV + JSON + SVG files. docs/bench.md says what the columns mean.
#include "cli.hpp"
#include "gnuplot_data.hpp"
#include "output_file.hpp"
#include <mechgraph/host/terminal_output.hpp>
#include "results_folder.hpp"
#include "spawn.hpp"
#include "options.hpp"

#include <mechgraph/bench_plot.hpp>
#include <mechgraph/bounded_read.hpp>
#include <mechgraph/csv.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/json_writer.hpp>
#include <mechgraph/knob_bench.hpp>
#include <mechgraph/text_escape.hpp>

#include <spdlog/spdlog.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace mechgraph::cli {
namespace {

std::string number_text(double x, const char* format = "%.3g") {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, format, x);
  return buffer;
}

// A number JSON can hold, or null (an unknown floor is infinite).
void finite_or_null(JsonWriter& json, double x) {
  if (std::isfinite(x)) json.value(x);
  else json.null();
}

// The error as the table shows it: "< floor" below the reference's floor, "value +- uncertainty"
// for Monte Carlo.
std::string error_text(const KnobStudy& study, const KnobTrial& t) {
  if (t.below_floor) return "< " + number_text(t.reference_floor, "%.2g");
  std::string text = number_text(t.max_relative_error, "%.3g");
  if (study.monte_carlo) text += " +- " + number_text(t.error_uncertainty, "%.2g");
  return text;
}

// How the study's reference was found, in one line.
std::string reference_line(const KnobStudy& study) {
  if (study.monte_carlo)
    return "error: the relative standard deviation of the outputs over " + std::to_string(study.seeds) +
           " independent seeds, +- its standard error";
  std::string line = "reference: " + study.knob + " = " + study.reference;
  if (study.reference_steps > 0)
    line += " (" + std::to_string(study.reference_steps) + (study.reference_steps == 1 ? " step" : " steps") + " tighter)";
  line += "; " + study.stopped;
  if (!study.floor_output.empty() && std::isfinite(study.floor) && study.floor > 0) line += " (most in " + study.floor_output + ")";
  return line;
}

void write_json(std::ostream& os, const KnobBench& bench, const std::vector<KnobAdvice>& advice, double tolerance) {
  JsonWriter json(os);
  json.begin_object().key("tolerance").value(tolerance).key("advice").begin_array();
  for (const KnobAdvice& a : advice) {
    json.begin_object().key("node").value(a.node).key("knob").value(a.knob);
    json.key("recommended");
    if (a.recommended) json.value(bench.trials[*a.recommended].setting);
    else json.null();
    json.key("default_off_front").value(a.current_off_front).key("text").value(a.text).end_object();
  }
  json.end_array();
  json.key("knobs").begin_array();
  for (const KnobStudy& k : bench.knobs) {
    json.begin_object().key("node").value(k.node).key("type").value(k.type).key("knob").value(k.knob);
    json.key("measured").value(k.not_measured.empty());
    if (!k.not_measured.empty()) {
      json.key("not_measured").value(k.not_measured).end_object();
      continue;
    }
    json.key("monte_carlo").value(k.monte_carlo);
    if (k.monte_carlo) {
      json.key("seeds").value(static_cast<long>(k.seeds));
    } else {
      json.key("reference").value(k.reference).key("reference_steps").value(static_cast<long>(k.reference_steps));
      json.key("reference_floor");
      finite_or_null(json, k.floor);
      json.key("floor_output").value(k.floor_output).key("converged").value(k.converged);
    }
    json.key("how").value(k.stopped).end_object();
  }
  json.end_array();
  json.key("trials").begin_array();
  for (const KnobTrial& t : bench.trials) {
    json.begin_object();
    json.key("node").value(t.node).key("type").value(t.type).key("knob").value(t.knob).key("setting").value(t.setting);
    json.key("default").value(t.is_default);
    if (t.failure.empty()) {
      json.key("seconds").value(t.seconds).key("max_relative_error").value(t.max_relative_error);
      json.key("error_uncertainty").value(t.error_uncertainty).key("reference_floor");
      finite_or_null(json, t.reference_floor);
      json.key("below_floor").value(t.below_floor);
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

void write_csv(std::ostream& os, const KnobBench& bench) {
  os << "node,type,knob,setting,default,on_front,seconds,max_relative_error,error_uncertainty,reference_floor,below_floor,"
        "worst_output,work,failure,not_measured\n";
  for (const KnobStudy& k : bench.knobs) {
    if (!k.not_measured.empty()) {
      os << csv_row({k.node, k.type, k.knob}) << ",,,,,,,,,," << csv_row({"", "", "", k.not_measured}) << "\n";
      continue;
    }
    for (std::size_t i = k.first_trial; i < k.first_trial + k.trial_count; ++i) {
      const KnobTrial& t = bench.trials[i];
      std::string work;
      for (const auto& [counter, amount] : t.work) work += (work.empty() ? "" : ";") + counter + "=" + number_text(amount, "%.17g");
      const std::string floor = std::isfinite(t.reference_floor) ? number_text(t.reference_floor, "%.6g") : "";
      os << csv_row({t.node, t.type, t.knob, t.setting}) << "," << (t.is_default ? 1 : 0) << "," << (t.on_front ? 1 : 0) << ","
         << number_text(t.seconds, "%.6g") << "," << number_text(t.max_relative_error, "%.6g") << ","
         << number_text(t.error_uncertainty, "%.6g") << "," << floor << "," << (t.below_floor ? 1 : 0) << ","
         << csv_row({t.worst_output, work, t.failure, ""}) << "\n";
    }
  }
}

void write_table(std::ostream& os, const KnobBench& bench, const std::vector<KnobAdvice>& advice) {
  for (std::size_t s = 0; s < bench.knobs.size(); ++s) {
    const KnobStudy& k = bench.knobs[s];
    const std::string group = k.node + " (" + k.type + ") knob " + k.knob;
    os << (s ? "\n" : "") << group;
    if (!k.not_measured.empty()) {
      os << ": " << terminal_text(k.not_measured) << "\n";
      continue;
    }
    os << "\n  " << terminal_text(reference_line(k)) << "\n";
    os << "  setting                   time [s]   error               worst output                   work\n";
    for (std::size_t i = k.first_trial; i < k.first_trial + k.trial_count; ++i) {
      const KnobTrial& t = bench.trials[i];
      char line[256];
      if (!t.failure.empty()) {
        std::snprintf(line, sizeof line, "  %-22s %s    failed: ", t.setting.c_str(), t.is_default ? "*" : " ");
        os << line << terminal_text(t.failure) << "\n";
        continue;
      }
      std::string work;
      for (const auto& [counter, amount] : t.work) work += (work.empty() ? "" : " ") + counter + "=" + number_text(amount, "%.0f");
      std::snprintf(line, sizeof line, "  %-22s %s%s %10.3g   %-18s  %-30s ", t.setting.c_str(), t.is_default ? "*" : " ",
                    t.on_front ? "P" : " ", t.seconds, error_text(k, t).c_str(), t.worst_output.c_str());
      os << line << work << "\n";
    }
    if (s < advice.size()) os << "  -> " << terminal_text(advice[s].text) << "\n";
  }
  os << "\n* the scene's setting; P on the Pareto front (no other setting both faster and more accurate).\n"
        "error: the largest relative error over the node's outputs, in the output named beside it, against the\n"
        "  knob's own converged reference (that knob tightened until successive values agree, the others at the\n"
        "  scene's settings); \"< x\": below the reference's own uncertainty x. Monte Carlo: the spread over seeds\n"
        "  +- its standard error. A setting is recommended only when error + uncertainty + floor is within --tol.\n";
}

// The work-precision plot: bench.dat and bench.gp from the core, drawn by gnuplot (Debian's
// gnuplot-nox) as SVG. Without gnuplot there is no bench.svg (a warning says so); with it, the SVG
// must come out whole, or nothing is published (IoError, exit 5): a full disk never leaves an
// empty or cut plot behind an exit 0.
void write_plot(const std::filesystem::path& dir, const KnobBench& bench) {
  const BenchPlot plot = bench_plot(bench);
  if (plot.script.empty()) return;  // no knob was measured
  write_file_whole(dir / "bench.dat", true, [&](std::ostream& data) { data << plot.data; });
  write_file_whole(dir / "bench.gp", true, [&](std::ostream& script) { script << plot.script; });
  const std::optional<std::filesystem::path> gnuplot = find_program("gnuplot");
  if (!gnuplot) {
    spdlog::warn("bench: gnuplot is not installed (apt-get install gnuplot-nox): no bench.svg, its data is in bench.dat");
    return;
  }
  // From an argument vector in the results folder: no shell reads the folder's name.
  const SpawnOutcome run = run_program(*gnuplot, {"bench.gp"}, dir, dir / "gnuplot.log", std::chrono::minutes(2));
  std::string svg;
  try {
    svg = read_bounded_file(dir / "bench.svg", std::size_t{256} << 20);
  } catch (const FileReadError&) {
  }
  if (!run.succeeded() || !is_whole_svg(svg)) {
    std::string log;
    try {
      log = read_bounded_file(dir / "gnuplot.log", 2048);
    } catch (const FileReadError&) {
    }
    throw IoError("bench: gnuplot could not draw bench.svg whole (" + (run.succeeded() ? std::string("the SVG is cut short") : run.describe()) +
                  "; disk full?): " + utf8_sanitized(log) + "; nothing was published");
  }
  // On the disk before the folder is put in place, as write_file_whole does for the others.
  const int fd = ::open((dir / "bench.svg").c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) io_failure("open", dir / "bench.svg", errno);
  const FileHandle handle(fd);
  if (::fsync(fd) != 0) io_failure("write", dir / "bench.svg", errno);
  std::filesystem::remove(dir / "gnuplot.log");
}

}  // namespace

int bench_command(const GlobalOptions& g, const std::vector<std::string>& args) {
  po::options_description visible("bench options");
  add_scene_options(visible);
  const KnobBenchOptions defaults;
  visible.add_options()("node", po::value<std::string>(), "only this node")(
      "steps", po::value<int>()->default_value(defaults.steps), "ladder: each knob from x 2^-steps to x 2^steps")(
      "repeats", po::value<int>()->default_value(defaults.repeats), "time = fastest of this many evaluations")(
      "tol", po::value<double>()->default_value(defaults.tolerance, "1e-9"),
      "recommend the cheapest setting whose error + uncertainty + reference floor is within this relative error; a "
      "reference is converged when successive values agree to 1e-3 x this")(
      "seeds", po::value<int>()->default_value(defaults.seeds), "Monte Carlo nodes: independent seeds per setting (2 to 100)")(
      "reference-steps", po::value<int>()->default_value(defaults.reference_steps),
      "at most this many steps tightening a knob for its reference (integer x2, real /4 a step)")(
      "reference-time", po::value<double>()->default_value(defaults.reference_seconds, "30"),
      "seconds one knob's reference search may take")("json", "print JSON on stdout")(
      "out", po::value<std::string>(), "also write bench.csv, bench.json and bench.svg into DIR (whole or not at all)")(
      "force", "replace the results in an existing --out DIR");
  po::variables_map vm;
  if (!parse_scene_command(args, visible, vm, "mechgraph bench SCENE [--node NAME] [--steps N] [--tol 1e-9] [--json] [--out DIR]"))
    return ok;
  KnobBenchOptions options;
  if (vm.count("node")) options.node = vm["node"].as<std::string>();
  options.steps = vm["steps"].as<int>();
  options.repeats = vm["repeats"].as<int>();
  options.seeds = vm["seeds"].as<int>();
  options.reference_steps = vm["reference-steps"].as<int>();
  options.reference_seconds = vm["reference-time"].as<double>();
  options.tolerance = vm["tol"].as<double>();
  if (options.steps < 0 || options.steps > 20) throw UsageError("--steps must be between 0 and 20");
  if (options.repeats < 1 || options.repeats > 100) throw UsageError("--repeats must be between 1 and 100");
  if (options.seeds < 2 || options.seeds > 100) throw UsageError("--seeds must be between 2 and 100");
  if (options.reference_steps < 0 || options.reference_steps > 40) throw UsageError("--reference-steps must be between 0 and 40");
  if (!(options.reference_seconds >= 0.0) || !std::isfinite(options.reference_seconds))
    throw UsageError("--reference-time must be a number of seconds >= 0");
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance)) throw UsageError("--tol must be > 0");
  if (vm.count("out")) check_results_folder(vm["out"].as<std::string>(), vm.count("force") > 0);
  const SceneSpec scene = load_scene(vm["scene"].as<std::string>());
  const PluginRegistry registry = plugins_for_scene(g, scene);
  const Graph graph = load_scene_graph(vm, scene, registry);
  // The ladders' work is checked before anything runs; each reference is checked step by step.
  const WorkBudget budget = work_budget(vm);
  options.max_work = budget.max_work;
  check_work_budget(graph, estimate_bench_work(graph, options), budget, 1, false);
  options.progress = [](std::size_t done, std::size_t total, const std::string& node) {
    spdlog::info("bench: node {} of {}: {}", done + 1, total, node);
  };
  KnobBench bench = bench_knobs(graph, options);
  const std::vector<KnobAdvice> advice = advise_knobs(bench, options.tolerance);
  spdlog::info("{} knob settings measured", bench.trials.size());
  // Built whole first: an error while writing leaves stdout empty, not a truncated document.
  std::ostringstream shown;
  if (vm.count("json")) write_json(shown, bench, advice, options.tolerance);
  else write_table(shown, bench, advice);
  if (vm.count("json")) std::cout << shown.str();
  else print_text(shown.str());  // node names and knob notes: shown through terminal_text
  if (vm.count("out")) {
    const std::filesystem::path dir = vm["out"].as<std::string>();
    write_results_folder(dir, vm.count("force") > 0, [&](const std::filesystem::path& staging) {
      write_file_whole(staging / "bench.csv", true, [&](std::ostream& csv) { write_csv(csv, bench); });
      write_file_whole(staging / "bench.json", true, [&](std::ostream& json) { write_json(json, bench, advice, options.tolerance); });
      write_plot(staging, bench);
    });
  }
  return ok;
}

}  // namespace mechgraph::cli
