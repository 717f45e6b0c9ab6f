// mechgraph merge FILE... [--out FILE]: the shards of one sweep (--shard I/N, e.g. a Slurm job
// array) put back together in case order, after checking that they belong to the same sweep
// (their manifests' fingerprints agree) and cover its cases exactly once.
#include "cli.hpp"
#include "options.hpp"
#include "sweep_file.hpp"

#include <mechgraph/csv.hpp>
#include <mechgraph/errors.hpp>

#include <spdlog/spdlog.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>

namespace mechgraph::cli {
namespace fs = std::filesystem;

int merge_command(const GlobalOptions&, const std::vector<std::string>& args) {
  po::options_description visible("merge options");
  visible.add_options()("help,h", "this text")("out", po::value<std::string>(), "write the merged rows to FILE (else stdout)")(
      "force", "replace an existing FILE");
  po::options_description all;
  all.add(visible).add_options()("files", po::value<std::vector<std::string>>()->required(), "shard files");
  po::positional_options_description positional;
  positional.add("files", -1);
  po::variables_map vm;
  if (!parse_options(args, visible, all, positional, vm, "mechgraph merge FILE... [--out FILE]   (e.g. mechgraph merge part-*.csv > all.csv)"))
    return ok;

  const auto files = vm["files"].as<std::vector<std::string>>();
  std::optional<SweepManifest> first;
  std::string first_file, header_line;
  struct Row {
    std::string line;
    std::string file;
  };
  std::map<std::size_t, Row> rows;
  std::size_t failed = 0;
  for (const std::string& f : files) {
    const SweepManifest m = read_manifest(f);
    if (!m.complete) throw UsageError(f + ": this shard is not complete (its manifest says so); finish it with --resume first");
    if (!first) {
      first = m;
      first_file = f;
    } else if (m.sweep != first->sweep || m.cases != first->cases || m.format != first->format) {
      throw UsageError(f + " belongs to another sweep than " + first_file + " (scene, --set, cases or columns differ)");
    }
    std::ifstream in(f);
    if (!in) throw IoError(f + ": cannot read");
    std::string line;
    bool header = m.format == RowFormat::csv;
    while (std::getline(in, line)) {
      if (header) {
        header = false;
        if (header_line.empty()) header_line = line;
        else if (line != header_line) throw UsageError(f + ": its columns differ from " + first_file + "'s");
        continue;
      }
      std::size_t pos = m.format == RowFormat::jsonl ? std::string("{\"case\":").size() : 0, c = 0, digits = 0;
      for (; pos < line.size() && std::isdigit(static_cast<unsigned char>(line[pos])); ++pos, ++digits) c = c * 10 + (line[pos] - '0');
      if (!digits || c >= m.cases) throw UsageError(f + ": a row that is not one of the sweep's " + std::to_string(m.cases) + " cases");
      auto [it, fresh] = rows.emplace(c, Row{line, f});
      if (!fresh) throw UsageError("case " + std::to_string(c) + " is in both " + it->second.file + " and " + f);
    }
  }
  if (rows.size() != first->cases) {
    std::string missing;
    std::size_t count = 0;
    for (std::size_t c = 0; c < first->cases; ++c)
      if (!rows.count(c) && count++ < 10) missing += (missing.empty() ? "" : ", ") + std::to_string(c);
    throw UsageError("the files hold " + std::to_string(rows.size()) + " of the sweep's " + std::to_string(first->cases) +
                     " cases; missing: " + missing + (count > 10 ? ", ..." : "") + " (is a shard absent?)");
  }

  auto write = [&](std::ostream& os) {
    if (!header_line.empty()) os << header_line << "\n";
    for (const auto& [c, row] : rows) os << row.line << "\n";
  };
  if (!vm.count("out")) {
    write(std::cout);
    std::cout.flush();
    if (!std::cout) throw IoError("standard output: cannot write");
  } else {
    const fs::path out = vm["out"].as<std::string>();
    if (fs::exists(out) && !vm.count("force")) throw UsageError(out.string() + " exists; use --force to replace it");
    const fs::path staging = out.string() + ".tmp";
    {
      std::ofstream os(staging);
      write(os);
      os.close();
      if (!os) throw IoError(staging.string() + ": cannot write");
    }
    fs::rename(staging, out);
  }
  (void)failed;
  spdlog::info("merge: {} cases from {} files, each once", rows.size(), files.size());
  return ok;
}

}  // namespace mechgraph::cli
