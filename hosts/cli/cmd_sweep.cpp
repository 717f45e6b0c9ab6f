// mechgraph sweep SCENE (--vary NAME=FROM:TO:N ... | --cases FILE.csv | --sample NAME=LO:HI ... --n N --seed S)
//                 [--threads N] [--out FILE] [--shard I/N|auto] [--resume] [--set ...] [--outputs a.b,c.d]
//                 [--format csv|jsonl] [--cache-size N] [--force]
#include "cli.hpp"
#include "options.hpp"
#include "stop_on_signals.hpp"
#include "sweep_file.hpp"
#include "sweep_fingerprint.hpp"
#include "sweep_progress.hpp"
#include <mechgraph/host/study_run.hpp>
#include <mechgraph/host/sweep_rows.hpp>

#include <mechgraph/bounded_read.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/csv.hpp>
#include <mechgraph/hash.hpp>
#include <mechgraph/sweep/case_estimate.hpp>
#include <mechgraph/sweep/case_table.hpp>
#include <mechgraph/sweep/sweep_runner.hpp>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <atomic>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <thread>

namespace mechgraph::cli {
namespace {


struct Shard {
  std::size_t index = 0, count = 1;
};

// The limits of the numbers a sweep's command line takes (documented in --help and the README).
constexpr std::size_t max_shards = 1000000;         // --shard I/N: N at most 10^6
constexpr std::size_t max_task_id = 1000000000;     // a Slurm array task id or bound

// A whole number from 0 to `limit`: digits only (no sign, no space, no exponent), so "-1" cannot
// wrap to 2^64 - 1 and 18446744073709551615 cannot overflow what follows.
std::size_t parse_count(const std::string& text, const std::string& what, std::size_t limit) {
  const bool digits = !text.empty() && text.size() <= 19 && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (!digits) throw UsageError(what + ": '" + excerpt(text, 40) + "' is not a whole number from 0 to " + std::to_string(limit));
  const unsigned long long v = std::strtoull(text.c_str(), nullptr, 10);
  if (v > limit) throw UsageError(what + ": " + text + " is more than " + std::to_string(limit));
  return static_cast<std::size_t>(v);
}

Shard parse_shard(const std::string& text) {
  Shard shard;
  if (text == "auto") {
    const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
    const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
    const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
    if (!id || !count)
      throw UsageError("--shard auto needs SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT (run it as a Slurm job array), or give --shard I/N");
    const std::size_t first = min ? parse_count(min, "SLURM_ARRAY_TASK_MIN", max_task_id) : 0;
    const std::size_t task = parse_count(id, "SLURM_ARRAY_TASK_ID", max_task_id);
    if (task < first)
      throw UsageError("SLURM_ARRAY_TASK_ID " + std::to_string(task) + " is below SLURM_ARRAY_TASK_MIN " + std::to_string(first));
    shard.index = task - first;
    shard.count = parse_count(count, "SLURM_ARRAY_TASK_COUNT", max_shards);
    if (shard.count == 0 || shard.index >= shard.count)
      throw UsageError("SLURM_ARRAY_TASK_ID " + std::to_string(task) + " - SLURM_ARRAY_TASK_MIN " + std::to_string(first) +
                       " must be below SLURM_ARRAY_TASK_COUNT " + std::to_string(shard.count) + " (a job array of consecutive tasks)");
    // The shards are the tasks min, min + 1, ...: an array with a step (--array=0-6:2) or with gaps
    // (--array=0,2,5) would leave some out, found only by merge at the end. Refused in every task.
    if (const char* step = std::getenv("SLURM_ARRAY_TASK_STEP"); step && parse_count(step, "SLURM_ARRAY_TASK_STEP", max_task_id) != 1)
      throw UsageError(std::string("SLURM_ARRAY_TASK_STEP is ") + step + ": --shard auto takes a job array of consecutive tasks "
                       "(--array=0-N-1, no step), or give --shard I/N");
    if (const char* max = std::getenv("SLURM_ARRAY_TASK_MAX")) {
      const std::size_t last = parse_count(max, "SLURM_ARRAY_TASK_MAX", max_task_id);
      if (last < first || last - first + 1 != shard.count)
        throw UsageError("SLURM_ARRAY_TASK_MIN " + std::to_string(first) + " to MAX " + std::to_string(last) + " are not " +
                         std::to_string(shard.count) + " consecutive tasks (SLURM_ARRAY_TASK_COUNT): --shard auto takes a job array "
                         "without gaps (--array=0-N-1), or give --shard I/N");
    }
  } else {
    const auto slash = text.find('/');
    if (slash == std::string::npos) throw UsageError("--shard " + excerpt(text) + ": expected I/N (0 <= I < N) or auto");
    shard.index = parse_count(text.substr(0, slash), "--shard I", max_shards);
    shard.count = parse_count(text.substr(slash + 1), "--shard N", max_shards);
  }
  if (shard.count == 0 || shard.index >= shard.count)
    throw UsageError("--shard " + excerpt(text) + ": needs 0 <= I < N, got I = " + std::to_string(shard.index) + ", N = " + std::to_string(shard.count));
  return shard;
}

CaseTable make_cases(const po::variables_map& vm, const SceneSpec& scene, const PluginRegistry& registry, const Graph& graph,
                     const std::vector<Override>& overrides) {
  const int ways = static_cast<int>(vm.count("vary") > 0) + static_cast<int>(vm.count("cases") > 0) + static_cast<int>(vm.count("sample") > 0) +
                   static_cast<int>(vm.count("study") > 0);
  if (ways != 1)
    throw UsageError("give the cases one way: --vary NAME=FROM:TO:N ..., --cases FILE.csv, --sample NAME=LO:HI ... --n N, or --study");
  if (vm.count("study")) {
    // The cases of the scene's uncertainty study, every one fixed by its index: shards of a Slurm
    // array each run theirs, `merge` joins them and `mechgraph study SCENE --rows FILE` analyses.
    if (vm.count("n")) throw UsageError("--study takes its sample count from the scene's uncertainty block or --samples, not --n");
    StudySpec spec = study_spec_of(scene, registry);
    apply_study_options(spec, vm.count("samples") ? vm["samples"].as<std::string>() : "", vm.count("method") ? vm["method"].as<std::string>() : "",
                        vm.count("seed") ? std::to_string(vm["seed"].as<std::uint64_t>()) : "");
    check_study_parameters(spec, graph, scene, registry, overrides);
    return make_study_cases(spec);
  }
  if (vm.count("samples") || vm.count("method")) throw UsageError("--samples and --method go with --study");
  if (!vm.count("sample") && (vm.count("n") || vm.count("seed"))) throw UsageError("--n and --seed go with --sample or --study");
  if (vm.count("vary")) {
    std::vector<VarySpec> specs;
    for (const std::string& v : vm["vary"].as<std::vector<std::string>>()) specs.push_back(parse_vary(v));
    return make_grid(specs);
  }
  if (vm.count("cases")) return read_cases_csv(vm["cases"].as<std::string>());
  if (!vm.count("n")) throw UsageError("--sample needs --n N, the number of cases");
  std::vector<SampleSpec> specs;
  for (const std::string& s : vm["sample"].as<std::vector<std::string>>()) specs.push_back(parse_sample(s));
  const std::size_t n = parse_count(vm["n"].as<std::string>(), "--n", max_sweep_cases);
  if (n == 0) throw UsageError("--n 0: a sample needs at least one case");
  return make_latin_hypercube(specs, n, vm.count("seed") ? vm["seed"].as<std::uint64_t>() : 1);
}


}  // namespace

int sweep_command(const GlobalOptions& g, const std::vector<std::string>& args) {
  po::options_description visible("sweep options");
  add_scene_options(visible);
  visible.add_options()
      ("vary", po::value<std::vector<std::string>>()->composing(), "a grid axis: NAME=FROM:TO:N (ends included) or NAME=A,B,C; several make a full grid")
      ("cases", po::value<std::string>(), "cases from CSV: header of names ('name' or 'name [unit]'), one case per row")
      ("sample", po::value<std::vector<std::string>>()->composing(), "a Latin hypercube variable: NAME=LO:HI")
      ("n", po::value<std::string>(), "cases to sample (with --sample), 1 to 2.5 x 10^8")
      ("study", "the cases of the scene's uncertainty study (its uncertainty: block; mechgraph study SCENE --rows FILE analyses them)")
      ("samples", po::value<std::string>(), "with --study: base samples N (default: the scene's)")
      ("method", po::value<std::string>(), "with --study: monte_carlo, latin_hypercube or sobol (default: the scene's)")
      ("seed", po::value<std::uint64_t>(), "seed of the sample (default 1) or, with --study, of the study's design (default: the scene's): the same seed, the same cases")
      ("threads", po::value<std::string>()->default_value("0"), "worker threads, 0 to 1024 (0: one per core)")
      ("out", po::value<std::string>(), "write rows to FILE (appended as they come, complete under its name at the end; FILE.json says which sweep)")
      ("format", po::value<std::string>()->default_value("csv"), "csv or jsonl")
      ("outputs", po::value<std::string>(), "columns: node.port,node.port (default: the scene's outputs and report cells)")
      ("shard", po::value<std::string>(), "I/N: run every N-th case from I (0-based, N at most 10^6); auto: from SLURM_ARRAY_TASK_ID/MIN/COUNT")
      ("resume", "go on with the unfinished FILE.part of the same sweep")
      ("force", "replace an existing FILE or unfinished FILE.part that mechgraph wrote (FILE.json says so)")
      ("cache-size", po::value<std::string>()->default_value(std::to_string(MemoCache::default_capacity)),
       "node results kept in the memo cache, 0 to 10^9 (least recently used dropped)")
      ("block-size", po::value<std::string>()->default_value(std::to_string(SweepOptions::default_block_size)),
       "cases evaluated together when every node on the path can (the block path), 0 to 10^6; 0 or 1: every case alone. The rows are the same");
  po::variables_map vm;
  if (!parse_scene_command(args, visible, vm,
                           "mechgraph sweep SCENE (--vary NAME=FROM:TO:N ... | --cases FILE.csv | --sample NAME=LO:HI ... --n N [--seed S] | --study)\n"
                           "                       [--threads N] [--out FILE] [--format csv|jsonl] [--shard I/N|auto] [--resume]\n"
                           "                       [--set NAME=VALUE ...] [--outputs a.b,c.d] [--cache-size N] [--block-size N] [--force]"))
    return ok;
  const std::string format_name = vm["format"].as<std::string>();
  if (format_name != "csv" && format_name != "jsonl") throw UsageError("--format " + format_name + ": valid formats are csv, jsonl");
  const RowFormat format = format_name == "csv" ? RowFormat::csv : RowFormat::jsonl;
  if (vm.count("resume") && !vm.count("out")) throw UsageError("--resume needs --out FILE (rows on stdout cannot be resumed)");
  if (vm.count("resume") && vm.count("force")) throw UsageError("--resume and --force contradict each other");
  // The numbers of the command line are checked before plugins and the scene load: a typo is told at once.
  const unsigned threads = static_cast<unsigned>(parse_count(vm["threads"].as<std::string>(), "--threads", max_threads));
  const Shard shard = vm.count("shard") ? parse_shard(vm["shard"].as<std::string>()) : Shard{};
  if (vm.count("n")) parse_count(vm["n"].as<std::string>(), "--n", max_sweep_cases);
  const std::size_t cache_size = parse_count(vm["cache-size"].as<std::string>(), "--cache-size", 1000000000);
  const std::size_t block_size = parse_count(vm["block-size"].as<std::string>(), "--block-size", 1000000);

  const std::string scene_file = vm["scene"].as<std::string>();
  SceneSpec scene = load_scene(scene_file);
  const PluginRegistry registry = plugins_for_scene(g, scene);
  const auto sets = vm.count("set") ? vm["set"].as<std::vector<std::string>>() : std::vector<std::string>{};
  std::vector<Override> overrides;
  for (const std::string& s : sets) overrides.push_back(parse_override(s));
  const Graph graph = build_sweep_graph(scene, registry, overrides,
                                       vm.count("outputs") ? std::optional<std::string>(vm["outputs"].as<std::string>()) : std::nullopt);
  CaseTable table = make_cases(vm, scene, registry, graph, overrides);
  const CaseBinder binder(graph, scene, registry, overrides, table.variables);
  if (vm.count("vary")) read_bare_numbers_in_list_unit(table, binder);

  SweepOptions options;
  for (std::size_t i = shard.index; i < table.size(); i += shard.count) options.cases.push_back(i);
  options.threads = threads;
  options.block_size = block_size;
  if (options.threads == 0) options.threads = std::max(1u, std::thread::hardware_concurrency());
  // The work of every case of this shard, each with its own values (a cases file's, a grid's, a
  // sample's), against the budget, and the memory of the largest case times the threads beside the
  // table of cases and their order (a sweep's
  // default work budget is larger: its cases are many by intent, and memoised nodes make the
  // estimate an upper bound).
  WorkBudget budget = work_budget(vm);
  if (vm["max-work"].defaulted()) budget.max_work = sweep_default_max_work;
  check_sweep_budget(graph, binder, table, options.cases, beside_the_table(budget, table, options.cases.size()), options.threads);
  options.stop = &stop_on_signals_flag();

  SweepManifest manifest;
  manifest.sweep = sweep_fingerprint(scene_file, sets, table, graph, format);
  manifest.cases = table.size();
  manifest.shard = shard.index;
  manifest.shards = shard.count;
  manifest.scene = scene_file;
  manifest.origin = table.origin;
  manifest.format = format;
  manifest.inputs = table.variables.size();
  const RowRules rules{format, table.size(), shard.index, shard.count, table.variables.size(),
                       [&table](std::size_t i, std::size_t v) { return table.shown(i, v); }};
  SweepFile file(vm.count("out") ? vm["out"].as<std::string>() : std::string(), manifest, vm.count("resume") > 0,
                 vm.count("force") > 0, rules);

  SweepRows rows(graph, table, format);
  std::size_t written = 0, failed = 0;
  if (!file.resumed_cases().empty() || !file.resumed_header().empty()) {
    const auto& done = file.resumed_cases();
    for (std::size_t r = 0; r < done.size(); ++r)
      if (r >= options.cases.size() || done[r] != options.cases[r])
        throw UsageError(file.path().string() + ".part: row " + std::to_string(r + 1) + " holds case " + std::to_string(done[r]) +
                         " where this sweep has case " + (r < options.cases.size() ? std::to_string(options.cases[r]) : "none"));
    if (!file.resumed_header().empty()) rows.adopt(file.resumed_header());
    written = done.size();
    failed = file.resumed_failed();
    options.cases.erase(options.cases.begin(), options.cases.begin() + static_cast<long>(done.size()));
    spdlog::info("sweep: resuming after {} cases already written; {} to go", written, options.cases.size());
  }

  const std::size_t total = written + options.cases.size();
  SweepProgress progress(total, spdlog::get_level() <= spdlog::level::info);
  // Rows go out in blocks (64 KiB, or every quarter second when cases are slow), whole rows only:
  // what a killed sweep leaves is still a prefix of whole rows for --resume.
  std::string pending;
  auto last_flush = std::chrono::steady_clock::now();
  auto flush = [&] {
    if (!pending.empty()) file.write(pending);
    pending.clear();
    last_flush = std::chrono::steady_clock::now();
  };
  auto put = [&](const CaseResult& r) {
    rows.append_line(pending, r, exit_code_of(r.failure));
    ++written;
    if (r.failure != CaseFailure::none) ++failed;
    if (pending.size() >= (std::size_t{1} << 16) || std::chrono::steady_clock::now() - last_flush > std::chrono::milliseconds(250)) flush();
  };
  RowSequencer sequence(rows, [&] { if (format == RowFormat::csv) file.write(csv_row(rows.header()) + "\n"); }, put);
  MemoCache cache(cache_size);
  SweepSummary summary;
  {
    const StopOnSignals on_signal;  // Ctrl-C and Slurm's SIGTERM let the started cases finish and their rows land
    summary = run_sweep(graph, binder, table, cache, options, [&](CaseResult&& r) {
      sequence(std::move(r));
      progress.update(written, failed);
    });
  }
  sequence.finish();
  flush();
  progress.finish(written, failed);
  const bool complete = written == total;
  file.finish(complete, written, failed);
  spdlog::info("sweep: {} cases in {:.3g} s ({:.4g}/s on {} threads), {} failed; {} in blocks; memo cache {} hits, {} misses, {} dropped",
               summary.run, summary.seconds, summary.seconds > 0 ? summary.run / summary.seconds : 0.0, options.threads,
               failed, summary.in_blocks, cache.hits(), cache.misses(), cache.evictions());
  if (!complete) {
    spdlog::warn("sweep stopped: {} of {} cases written{}", written, total,
                 file.to_stdout() ? "" : "; 'mechgraph sweep ... --resume' goes on from there");
    return interrupted;
  }
  if (failed) spdlog::warn("sweep: {} of {} cases failed; their rows give the error and its exit class", failed, total);
  if (!file.to_stdout()) spdlog::info("sweep: rows in {}", file.path().string());
  return ok;
}

}  // namespace mechgraph::cli
