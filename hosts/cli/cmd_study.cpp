// mechgraph study SCENE [--samples N] [--method M] [--seed S] [--threads N] [--json] [--out DIR]
//                       [--rows FILE] [--set ...] [--outputs a.b,c.d]
// An uncertainty study of the scene's `uncertainty:` block: its cases run on the worker pool
// (study_run.hpp), or read back from the rows of `mechgraph sweep SCENE --study` (its shards
// merged), then analysed: per output moments, quantiles, histogram, Cp/Cpk and ppm, Sobol'
// indices; per event its probability (docs/methods/uncertainty.md).
#include "cli.hpp"
#include "line_reader.hpp"
#include "options.hpp"
#include "provenance.hpp"
#include "stop_on_signals.hpp"
#include "results_folder.hpp"
#include "study_page.hpp"
#include "study_text.hpp"
#include <mechgraph/host/study_run.hpp>
#include "sweep_file.hpp"
#include "sweep_fingerprint.hpp"
#include <mechgraph/host/sweep_rows.hpp>
#include <mechgraph/host/terminal_output.hpp>

#include <mechgraph/csv.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/sweep/case_estimate.hpp>
#include <mechgraph/sweep/case_table.hpp>

#include <spdlog/spdlog.h>

#include <atomic>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

namespace mechgraph::cli {
namespace {

// The header of an output's column in the rows of a sweep of the study (sweep_rows.hpp).
std::string study_column_name(const Graph& graph, const StudyColumn& c) {
  for (std::size_t j = 0; j < graph.outputs.size(); ++j)
    if (graph.outputs[j].label == c.label) return sweep_column_name(graph, j);
  const std::string u = study_unit(c);
  return u.empty() ? c.label : c.label + " [" + u + "]";
}

// The rows of `mechgraph sweep SCENE --study` (one file, or shards merged): each case once, its
// inputs those of this study's design (so the seed, method and samples agree), its outputs read
// back to the doubles the rows were written from.
StudyData read_study_rows(const std::string& file, const Graph& graph, const CaseTable& table, const std::vector<StudyColumn>& columns) {
  LineReader reader(file, max_row_bytes);
  std::string line;
  if (!reader.next(line)) throw UsageError(file + ": empty; expected the rows of 'mechgraph sweep SCENE --study'");
  // Rows that went through another tool (a byte order mark, CR LF line ends) are read past them.
  strip_foreign_line_marks(line, 1);
  if (line.starts_with("{"))
    throw UsageError(file + ":1: rows in JSON Lines; --rows reads the CSV rows of 'mechgraph sweep SCENE --study' (--format csv, the default)");
  // A line that is not CSV (an unclosed quote) is refused at its line.
  const auto cells_of = [&](const std::string& text, std::size_t number) {
    try {
      return split_csv_line(text);
    } catch (const std::invalid_argument& e) {
      throw UsageError(file + ":" + std::to_string(number) + ": " + e.what());
    }
  };
  const std::vector<std::string> header = cells_of(line, 1);
  const auto column_of = [&](const std::string& name) -> std::optional<std::size_t> {
    for (std::size_t k = 0; k < header.size(); ++k)
      if (header[k] == name) return k;
    return std::nullopt;
  };
  const auto exit_column = column_of("exit"), error_column = column_of("error");
  if (header.empty() || header[0] != "case" || !exit_column)
    throw UsageError(file + ":1: not the rows of a sweep (a header 'case', inputs, outputs, 'exit', 'error')");
  std::vector<std::size_t> at(columns.size());
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const auto k = column_of(study_column_name(graph, columns[c]));
    if (!k) throw UsageError(file + ":1: no column for output '" + columns[c].label + "' (the study reads the scene's scalar outputs)");
    at[c] = *k;
  }
  const std::size_t n = table.size(), inputs = table.variables.size();
  StudyData data;
  data.outputs = columns;
  data.values.assign(columns.size(), std::vector<double>(n, std::nan("")));
  data.failures.assign(n, CaseFailure::none);
  std::vector<bool> seen(n, false);
  std::size_t rows = 0;
  while (reader.next(line)) {
    strip_foreign_line_marks(line, reader.number());
    const std::string where = file + ":" + std::to_string(reader.number()) + ": ";
    const std::vector<std::string> cells = cells_of(line, reader.number());
    if (cells.size() != header.size()) throw UsageError(where + std::to_string(cells.size()) + " cells, the header has " + std::to_string(header.size()));
    std::size_t i = 0;
    const auto [p, ec] = std::from_chars(cells[0].data(), cells[0].data() + cells[0].size(), i);
    if (ec != std::errc() || p != cells[0].data() + cells[0].size() || i >= n)
      throw UsageError(where + "case '" + excerpt(cells[0], 40) + "' is not a case of this study (0 to " + std::to_string(n - 1) + ")");
    if (seen[i]) throw UsageError(where + "case " + std::to_string(i) + " appears twice");
    seen[i] = true;
    ++rows;
    for (std::size_t v = 0; v < inputs; ++v)
      if (cells[1 + v] != table.shown(i, v))
        throw UsageError(where + "case " + std::to_string(i) + " has " + table.variables[v].name + " = " + excerpt(cells[1 + v], 40) +
                         " where this study's design has " + table.shown(i, v) + ": rows of another seed, method or sample count");
    const std::string& exit = cells[*exit_column];
    if (exit != "0" && exit != "2" && exit != "3")
      throw UsageError(where + "case " + std::to_string(i) + ": the exit '" + excerpt(exit, 40) + "' is not 0, 2 or 3");
    if (exit != "0") {
      data.record_failure(i, exit == "2" ? CaseFailure::scene : CaseFailure::evaluation, error_column ? cells[*error_column] : std::string());
      continue;
    }
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const std::string& cell = cells[at[c]];
      double x = 0;
      const auto [q, e] = std::from_chars(cell.data(), cell.data() + cell.size(), x);
      if (e != std::errc() || q != cell.data() + cell.size() || !std::isfinite(x))
        throw UsageError(where + "'" + excerpt(cell, 40) + "' is not a finite number (" + columns[c].label + ")");
      data.values[c][i] = x;
    }
  }
  if (rows != n)
    throw UsageError(file + ": " + std::to_string(rows) + " of the study's " + std::to_string(n) +
                     " cases; run the missing shards (or --resume) and merge them");
  return data;
}

std::string terminal_tables(const StudySpec& spec, const StudyAnswers& a) {
  std::ostringstream out;
  out << "Uncertainty study: " << to_string(spec.method) << ", " << spec.samples << " samples, seed " << spec.seed << ", "
      << a.cases << " evaluations (" << a.failed << " failed)\n\n";
  out << "parameter                      distribution\n";
  for (const UncertainParameter& p : spec.parameters) out << "  " << p.name << std::string(p.name.size() < 29 ? 29 - p.name.size() : 1, ' ') << p.written << "\n";
  const std::string level = confidence_percent(spec.confidence);
  out << "\nOutputs (intervals at " << level << " %)\n";
  for (const OutputAnswer& o : a.outputs) {
    const std::string u = study_unit(o.column);
    out << "\n" << o.column.label << (u.empty() ? "" : " [" + u + "]") << ": n " << o.moments.n;
    if (o.failed) out << " (" << o.failed << " failed)";
    out << "\n";
    if (o.moments.n == 0) continue;
    out << "  " << moments_text(o.moments) << "\n";
    for (const QuantileEstimate& q : o.quantiles)
      out << "  quantile " << study_number(q.level) << ": " << study_number(q.value) << " " << study_interval(q.interval) << "\n";
    if (o.capability) out << "  " << capability_text(o) << "\n";
  }
  bool any_sobol = false;
  for (const OutputAnswer& o : a.outputs) any_sobol = any_sobol || o.sobol.has_value();
  if (any_sobol) {
    out << "\nSobol' indices: first order (Saltelli 2010), total (Jansen), bootstrap intervals at " << level << " %\n";
    for (const OutputAnswer& o : a.outputs) {
      if (!o.sobol) continue;
      out << "\n" << o.column.label << " (" << o.sobol->samples << " base samples)\n";
      if (o.sobol->indices.empty())
        out << (o.sobol->samples < 2 ? "  (fewer than 2 base samples have a value in every one of their cases: no indices)\n"
                                     : "  (it does not vary over the samples: no parameter's share of its variance is defined)\n");
      for (std::size_t j = 0; j < o.sobol->indices.size(); ++j) {
        const SobolIndex& s = o.sobol->indices[j];
        const std::string& name = spec.parameters[j].name;
        out << "  " << name << std::string(name.size() < 28 ? 28 - name.size() : 1, ' ') << "S " << study_number(s.first) << " "
            << study_interval(s.first_interval) << "   ST " << study_number(s.total) << " " << study_interval(s.total_interval) << "\n";
      }
    }
  }
  if (!a.events.empty()) {
    out << "\nEvents (probability, Wilson and Clopper-Pearson intervals at " << level << " %)\n";
    for (const EventAnswer& e : a.events) {
      out << "  " << e.event->name << ": " << e.probability.events << " of " << e.probability.trials << " = " << study_number(e.probability.estimate)
          << " " << study_interval(e.probability.wilson) << " " << study_interval(e.probability.clopper_pearson);
      if (e.undecided) out << " (" << e.undecided << " cases without a value)";
      out << "\n";
    }
  }
  return out.str();
}

// The answers as CSV files, each number in its column's unit as the terminal shows them.
void write_csvs(const std::filesystem::path& dir, const StudySpec& spec, const StudyAnswers& a) {
  const auto put = [&](const std::string& name, const std::string& text) {
    std::ofstream f(dir / name, std::ios::binary);
    f << text;
    f.close();
    check_written(f, dir / name);
  };
  const auto cell = [](const std::optional<double>& x) {
    if (!x) return std::string();
    char buffer[32];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, *x);
    return std::string(buffer, end);
  };
  std::string summary = csv_row({"output", "unit", "n", "failed", "mean", "mean_lower", "mean_upper", "standard_deviation", "min", "max",
                                 "lower_limit", "upper_limit", "below", "above", "cp", "cpk", "ppm", "ppm_lower", "ppm_upper",
                                 "ppm_normal", "ppm_or_failed", "ppm_or_failed_lower", "ppm_or_failed_upper"}) + "\n";
  std::string quantiles = csv_row({"output", "unit", "level", "value", "lower", "upper"}) + "\n";
  std::string histograms = csv_row({"output", "unit", "bin_low", "bin_high", "count"}) + "\n";
  std::string sobol = csv_row({"output", "parameter", "first", "first_lower", "first_upper", "total", "total_lower", "total_upper"}) + "\n";
  for (const OutputAnswer& o : a.outputs) {
    const std::string u = study_unit(o.column);
    const Moments& m = o.moments;
    const bool any = m.n > 0;
    std::optional<double> cp, cpk, ppm, ppm_lo, ppm_hi, ppm_normal, ppm_failed, ppm_failed_lo, ppm_failed_hi;
    std::string below, above;  // cases below the lower limit and above the upper, with limits
    if (o.capability) {
      below = std::to_string(o.capability->below);
      above = std::to_string(o.capability->above);
      cp = o.capability->cp;
      cpk = o.capability->cpk;
      ppm = 1e6 * o.capability->out_of_spec.estimate;
      ppm_lo = 1e6 * *o.capability->out_of_spec.wilson.lower;
      ppm_hi = 1e6 * *o.capability->out_of_spec.wilson.upper;
      ppm_normal = o.capability->ppm_normal;
      ppm_failed = 1e6 * o.capability->out_of_spec_or_failed.estimate;
      ppm_failed_lo = 1e6 * *o.capability->out_of_spec_or_failed.wilson.lower;
      ppm_failed_hi = 1e6 * *o.capability->out_of_spec_or_failed.wilson.upper;
    }
    const auto opt = [any](double x) { return any ? std::optional<double>(x) : std::nullopt; };
    summary += csv_row({o.column.label, u, std::to_string(m.n), std::to_string(o.failed), cell(opt(m.mean)), cell(m.mean_interval.lower),
                        cell(m.mean_interval.upper), cell(opt(m.standard_deviation)), cell(opt(m.min)), cell(opt(m.max)), cell(o.lower),
                        cell(o.upper), below, above, cell(cp), cell(cpk), cell(ppm), cell(ppm_lo), cell(ppm_hi), cell(ppm_normal),
                        cell(ppm_failed), cell(ppm_failed_lo), cell(ppm_failed_hi)}) + "\n";
    for (const QuantileEstimate& q : o.quantiles)
      quantiles += csv_row({o.column.label, u, cell(q.level), cell(q.value), cell(q.interval.lower), cell(q.interval.upper)}) + "\n";
    for (std::size_t k = 0; k < o.histogram.counts.size(); ++k)
      histograms += csv_row({o.column.label, u, cell(o.histogram.low + static_cast<double>(k) * o.histogram.width),
                             cell(o.histogram.low + static_cast<double>(k + 1) * o.histogram.width), std::to_string(o.histogram.counts[k])}) + "\n";
    if (o.sobol)
      for (std::size_t j = 0; j < o.sobol->indices.size(); ++j) {
        const SobolIndex& s = o.sobol->indices[j];
        sobol += csv_row({o.column.label, spec.parameters[j].name, cell(s.first), cell(s.first_interval.lower), cell(s.first_interval.upper),
                          cell(s.total), cell(s.total_interval.lower), cell(s.total_interval.upper)}) + "\n";
      }
  }
  std::string events = csv_row({"event", "events", "trials", "undecided", "probability", "wilson_lower", "wilson_upper",
                                "clopper_pearson_lower", "clopper_pearson_upper"}) + "\n";
  for (const EventAnswer& e : a.events) {
    const Proportion& p = e.probability;
    events += csv_row({e.event->name, std::to_string(p.events), std::to_string(p.trials), std::to_string(e.undecided), cell(p.estimate),
                       cell(p.wilson.lower), cell(p.wilson.upper), cell(p.clopper_pearson.lower), cell(p.clopper_pearson.upper)}) + "\n";
  }
  put("summary.csv", summary);
  put("quantiles.csv", quantiles);
  put("histograms.csv", histograms);
  if (spec.sensitivity) put("sobol.csv", sobol);
  put("events.csv", events);
}

}  // namespace

int study_command(const GlobalOptions& g, const std::vector<std::string>& args) {
  po::options_description visible("study options");
  add_scene_options(visible);
  visible.add_options()
      ("samples", po::value<std::string>(), "base samples N, 2 to 2.5 x 10^8 (default: the scene's, else 1000)")
      ("method", po::value<std::string>(), "monte_carlo, latin_hypercube or sobol (default: the scene's, else latin_hypercube)")
      ("seed", po::value<std::string>(), "seed of every random number (default: the scene's, else 1)")
      ("threads", po::value<std::string>()->default_value("0"), "worker threads, 0 to 1024 (0: one per core); the answers do not depend on it")
      ("outputs", po::value<std::string>(), "outputs to study: node.port,node.port (default: the scene's scalar outputs)")
      ("rows", po::value<std::string>(), "analyse the rows of 'mechgraph sweep SCENE --study' (shards merged) instead of running the cases")
      ("json", "print one JSON object on stdout (SI)")
      ("out", po::value<std::string>(), "also write study.json, report.html (histograms against spec limits, Sobol' chart) and CSVs (summary, quantiles, histograms, sobol, events) into DIR")
      ("force", "replace DIR when mechgraph wrote it");
  po::variables_map vm;
  if (!parse_scene_command(args, visible, vm,
                           "mechgraph study SCENE [--samples N] [--method M] [--seed S] [--threads N] [--rows FILE]\n"
                           "                       [--set NAME=VALUE ...] [--outputs a.b,c.d] [--json] [--out DIR]"))
    return ok;
  const std::string samples = vm.count("samples") ? vm["samples"].as<std::string>() : "";
  const std::string method = vm.count("method") ? vm["method"].as<std::string>() : "";
  const std::string seed = vm.count("seed") ? vm["seed"].as<std::string>() : "";
  const std::string& threads_text = vm["threads"].as<std::string>();
  unsigned threads = 0;
  if (const auto [p, ec] = std::from_chars(threads_text.data(), threads_text.data() + threads_text.size(), threads);
      ec != std::errc() || p != threads_text.data() + threads_text.size() || threads > max_threads)
    throw UsageError("--threads '" + excerpt(threads_text, 40) + "' is not a whole number from 0 to " + std::to_string(max_threads));
  if (vm.count("out")) check_results_folder(vm["out"].as<std::string>(), vm.count("force") > 0);
  const std::string scene_file = vm["scene"].as<std::string>();
  SceneSpec scene = load_scene(scene_file);
  const PluginRegistry registry = plugins_for_scene(g, scene);
  const auto sets = vm.count("set") ? vm["set"].as<std::vector<std::string>>() : std::vector<std::string>{};
  std::vector<Override> overrides;
  for (const std::string& s : sets) overrides.push_back(parse_override(s));
  const std::optional<std::string> outputs = vm.count("outputs") ? std::optional<std::string>(vm["outputs"].as<std::string>()) : std::nullopt;

  std::unique_ptr<StudyOutcome> outcome;
  WorkBudget budget = work_budget(vm);
  if (vm["max-work"].defaulted()) budget.max_work = sweep_default_max_work;
  if (vm.count("rows")) {
    // The design again (it depends on the seed alone), the values from the rows; what the study
    // holds and its bootstrap within the budget, as in process.
    const unsigned workers = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
    outcome = prepare_scene_study(scene, registry, overrides, std::nullopt, samples, method, seed, outputs, workers, &budget);
    outcome->threads = workers;
    const std::string rows_file = vm["rows"].as<std::string>();
    // The manifest beside the rows, read once: one that is there but unreadable or damaged is
    // refused (read_manifest_checked says why), never taken for none.
    std::optional<SweepManifest> manifest;
    if (kind_of(manifest_path(rows_file)) != "absent") {
      try {
        manifest = read_manifest_checked(rows_file);
      } catch (const UsageError& e) {
        throw UsageError(std::string(e.what()) + "; remove it to study the rows without checking where they come from");
      }
    }
    // Rows another mechgraph wrote would be refused row by row below as not this study's: say why.
    if (manifest)
      require_rows_format(*manifest, rows_file, "study them with the mechgraph that wrote them, or run the sweep again with this one");
    // Rows of another design: said before the rows are read. Their first rows may well be this
    // study's (a Sobol' or Monte Carlo design's first points do not depend on the sample count), and
    // the count of rows alone would call a complete file of another design a part of this one.
    if (manifest && !manifest->origin.empty() && manifest->origin != outcome->table.origin)
      throw UsageError(rows_file + ": rows of another design (" + excerpt(manifest->origin, 160) + ", " +
                       std::to_string(manifest->cases) + " cases); this study's is " + outcome->table.origin + ", " +
                       std::to_string(outcome->table.size()) + " cases: give the study the --samples, --method and --seed " +
                       "the sweep had, or the scene the sweep read");
    try {
      outcome->data = read_study_rows(rows_file, outcome->graph, outcome->table, outcome->columns);
    } catch (const UsageError& e) {
      throw UsageError(std::string(e.what()) + (manifest ? unrecorded_format_note(*manifest) : std::string()));
    }
    // Rows of this study, not of another scene, another --set or other files the scene reads: the
    // manifest beside them (sweep and merge write one) carries the sweep's fingerprint, which the
    // study's own must equal; the design's inputs (checked row by row first, which
    // names another seed, method or sample count) do not tell.
    if (manifest) {
      if (manifest->sweep != sweep_fingerprint(scene_file, sets, outcome->table, outcome->graph, RowFormat::csv))
        throw UsageError(rows_file + ": the rows of another sweep: the scene, a file it reads, --set or --outputs differ from those " +
                         "the rows were made with (mechgraph sweep " + excerpt(manifest->scene, 80) + " --study ...)" +
                         unrecorded_format_note(*manifest));
    } else {
      spdlog::warn("study: {} has no manifest beside it ({}): whether its rows come from this scene and these --set values "
                   "cannot be checked", rows_file, manifest_path(rows_file).filename().string());
    }
    // Ctrl-C or SIGTERM while the answers are made: none are reported (exit 130), as in process.
    {
      const StopOnSignals signals;
      finish_study(*outcome, &stop_on_signals_flag());
    }
    if (outcome->summary.stopped) {
      spdlog::warn("study stopped while its answers were computed from {}; nothing is reported", excerpt(rows_file, 200));
      return interrupted;
    }
  } else {
    {
      const StopOnSignals signals;
      outcome = run_scene_study(scene, registry, overrides, std::nullopt, samples, method, seed, outputs, budget, threads,
                                &stop_on_signals_flag());
    }
    const SweepSummary& summary = outcome->summary;
    if (summary.stopped) {
      if (summary.run == outcome->table.size())
        spdlog::warn("study stopped while its answers were computed, after all {} cases; nothing is reported "
                     "(to keep the cases: mechgraph sweep SCENE --study --out FILE, then mechgraph study SCENE --rows FILE)",
                     summary.run);
      else
        spdlog::warn("study stopped after {} of {} cases; nothing is reported from a part of the design "
                     "(to stop and go on: mechgraph sweep SCENE --study --out FILE, then --resume)", summary.run, outcome->table.size());
      return interrupted;
    }
    spdlog::info("study: {} cases in {:.3g} s, {} failed; {} in blocks", summary.run, summary.seconds, summary.failed, summary.in_blocks);
  }
  const StudySpec& spec = outcome->spec;
  const StudyAnswers& answers = outcome->answers;
  // Failed cases say why: the first one's message (the rest are in `mechgraph sweep SCENE --study`'s
  // error column). A study whose every case failed answers nothing: an error, with the exit class
  // of that first failure.
  if (const StudyData& data = outcome->data; data.first_failed) {
    const std::size_t first = *data.first_failed;
    const std::string why = "case " + std::to_string(first) + ": " + (data.first_error.empty() ? "(no message)" : data.first_error);
    if (answers.failed == answers.cases) {
      spdlog::error("study: every one of the {} cases failed, so nothing is answered; the first, {}", answers.cases, why);
      return exit_code_of(data.failures[first]);
    }
    spdlog::warn("study: {} of {} cases failed (counted in 'failed' and the events on failures); the first, {}", answers.failed,
                 answers.cases, why);
  }
  // The answers with how they were made: the program, the scene and its SHA-1, the --set values,
  // each node's parameters (provenance.hpp).
  std::ostringstream with_provenance;
  {
    JsonWriter w(with_provenance);
    write_study_json(w, spec, answers, [&](JsonWriter& j) { write_provenance(j, outcome->graph, registry, RunInputs{scene_file, sets}); });
  }
  const std::string json = with_provenance.str() + "\n";
  if (vm.count("out"))
    write_results_folder(vm["out"].as<std::string>(), vm.count("force") > 0, [&](const std::filesystem::path& dir) {
      std::ofstream f(dir / "study.json", std::ios::binary);
      f << json;
      f.close();
      check_written(f, dir / "study.json");
      write_csvs(dir, spec, answers);
      std::ofstream page(dir / "report.html", std::ios::binary);
      page << study_page(scene.title, spec, answers);
      page.close();
      check_written(page, dir / "report.html");
    });
  if (vm.count("json")) std::cout << json;
  else print_text(terminal_tables(spec, answers));
  return ok;
}

}  // namespace mechgraph::cli
