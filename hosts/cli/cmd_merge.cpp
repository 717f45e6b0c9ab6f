// mechgraph merge FILE... [--out FILE]: the shards of one sweep (--shard I/N, e.g. a Slurm job
// array) put back together in case order, after checking that they belong to the same sweep
// (their manifests' fingerprints agree) and cover its cases exactly once. Every row is checked as
// --resume checks it (RowChecker: cells, case number in range, in order, this shard's, numbers
// finite) and each manifest's case count is capped (10^7), so an edited or hostile file is refused
// naming FILE:line instead of being carried over or spun on. `--out FILE` is written whole (a
// temporary renamed over it), locked against a second writer, with a manifest of its own (one
// shard of one: a merged file can be resumed from, merged again, or replaced with --force).
#include "cli.hpp"
#include "options.hpp"
#include "output_file.hpp"
#include "sweep_file.hpp"

#include <mechgraph/csv.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/sweep/case_table.hpp>

#include <spdlog/spdlog.h>

#include <cstdio>
#include <iostream>
#include <map>
#include <sstream>

namespace mechgraph::cli {
namespace fs = std::filesystem;
namespace {

struct Merged {
  std::optional<SweepManifest> first;
  std::string first_file, header_line;
  std::map<std::size_t, std::string> rows;        // case -> line
  std::map<std::size_t, std::string> row_file;    // case -> the file it came from
  std::size_t failed = 0;
};

// Reads one complete shard into `merged`, checking every row.
void read_shard(const std::string& f, Merged& merged) {
  const SweepManifest m = read_manifest(f);
  if (!m.complete) throw UsageError(f + ": this shard is not complete (its manifest says so); finish it with --resume first");
  // Without the count of input columns the outputs could not be told from inputs and checked.
  if (!m.inputs) throw UsageError(f + ": its manifest does not say how many input columns the rows have; run the shard again");
  if (!merged.first) {
    merged.first = m;
    merged.first_file = f;
  } else if (m.sweep != merged.first->sweep || m.cases != merged.first->cases || m.format != merged.first->format) {
    throw UsageError(f + " belongs to another sweep than " + merged.first_file + " (scene, --set, cases or columns differ)");
  }
  std::istringstream in(read_user_file(f, max_rows_file_bytes, "merge"));
  RowChecker checker({m.format, m.cases, m.shard, m.shards, m.inputs, {}}, f);
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (number == 1 && m.format == RowFormat::csv) {
      checker.header(line, number);
      if (merged.header_line.empty()) merged.header_line = line;
      else if (line != merged.header_line) throw UsageError(f + ": its columns differ from " + merged.first_file + "'s");
      continue;
    }
    const RowChecker::Row row = checker.row(line, number);
    auto [it, fresh] = merged.rows.emplace(row.index, line);
    if (!fresh) throw UsageError("case " + std::to_string(row.index) + " is in both " + merged.row_file[row.index] + " and " + f);
    merged.row_file[row.index] = f;
    if (row.failed) ++merged.failed;
  }
}

}  // namespace

int merge_command(const GlobalOptions&, const std::vector<std::string>& args) {
  po::options_description visible("merge options");
  visible.add_options()("help,h", "this text")("out", po::value<std::string>(), "write the merged rows to FILE (else stdout)")(
      "force", "replace an existing FILE that mechgraph wrote (its manifest FILE.json says so)");
  po::options_description all;
  all.add(visible).add_options()("files", po::value<std::vector<std::string>>()->required(), "shard files");
  po::positional_options_description positional;
  positional.add("files", -1);
  po::variables_map vm;
  if (!parse_options(args, visible, all, positional, vm, "mechgraph merge FILE... [--out FILE]   (e.g. mechgraph merge part-*.csv > all.csv)"))
    return ok;

  // The output is locked and checked before the shards are read: a second merge is refused at once.
  std::optional<OutputLock> lock;
  const bool force = vm.count("force") > 0;
  if (vm.count("out")) {
    const fs::path out = vm["out"].as<std::string>();
    lock.emplace(out);
    if (kind_of(out) != "absent") {
      if (kind_of(out) == "a regular file" && !force) throw UsageError(out.string() + " exists; use --force to replace it");
      refuse_unless_ours(out, has_sweep_manifest(out), "--out");
    }
    if (kind_of(manifest_path(out)) != "absent" && !has_sweep_manifest(out))
      throw UsageError(manifest_path(out).string() + " is not a sweep manifest mechgraph wrote: it is left alone; choose another --out");
  }

  const auto files = vm["files"].as<std::vector<std::string>>();
  Merged merged;
  for (const std::string& f : files) read_shard(f, merged);
  const SweepManifest& first = *merged.first;
  if (merged.rows.size() != first.cases) {
    std::string missing;
    std::size_t count = 0;
    for (std::size_t c = 0; c < first.cases && count <= 10; ++c)
      if (!merged.rows.count(c) && count++ < 10) missing += (missing.empty() ? "" : ", ") + std::to_string(c);
    throw UsageError("the files hold " + std::to_string(merged.rows.size()) + " of the sweep's " + std::to_string(first.cases) +
                     " cases; missing: " + missing + (count > 10 ? ", ..." : "") + " (is a shard absent?)");
  }

  auto write = [&](std::ostream& os) {
    if (!merged.header_line.empty()) os << merged.header_line << "\n";
    for (const auto& [c, line] : merged.rows) os << line << "\n";
  };
  if (!vm.count("out")) {
    write(std::cout);
    std::cout.flush();
    if (!std::cout) throw IoError("standard output: cannot write");
  } else {
    const fs::path out = vm["out"].as<std::string>();
    write_file_whole(out, force, write);
    SweepManifest m = first;
    m.shard = 0;
    m.shards = 1;
    m.complete = true;
    m.rows = merged.rows.size();
    m.failed = merged.failed;
    write_manifest(out, m);
  }
  spdlog::info("merge: {} cases from {} files, each once", merged.rows.size(), files.size());
  return ok;
}

}  // namespace mechgraph::cli
