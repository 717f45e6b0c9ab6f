// mechgraph merge FILE... [--out FILE]: the shards of one sweep (--shard I/N, e.g. a Slurm job
// array) put back together in case order, after checking that they belong to the same sweep
// (their manifests' fingerprints agree, and their columns: the CSV headers, the JSON Lines keys)
// and cover its cases exactly once.

// Streaming: each shard's rows are in case order already (RowChecker refuses any other), so the
// shards are merged like sorted runs, one line of each in memory at a time (LineReader). Memory
// is bounded by the number of shards times the longest row, whatever the number of rows. On
// stdout nothing may come out before everything is checked, so the shards are read twice (once
// to check, once to write); `--out` is written once, into a temporary that a refusal removes. Every row is checked as
// --resume checks it (RowChecker: cells, case number in range, in order, this shard's, numbers
// finite) and each manifest's case count is capped (max_sweep_cases), so an edited or hostile file is refused
// naming FILE:line instead of being carried over or spun on. `--out FILE` is written whole (a
// temporary renamed over it), locked against a second writer, with a manifest of its own (one
// shard of one: a merged file can be resumed from, merged again, or replaced with --force).
#include "cli.hpp"
#include "line_reader.hpp"
#include "options.hpp"
#include "output_file.hpp"
#include "sweep_file.hpp"

#include <mechgraph/csv.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/sweep/case_table.hpp>

#include <spdlog/spdlog.h>

#include <sys/resource.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <queue>
#include <sstream>

namespace mechgraph::cli {
namespace fs = std::filesystem;
namespace {

struct Shard {
  std::string file;
  SweepManifest manifest;
};

// The manifests: every shard complete, of one sweep, saying how many input columns its rows have.
std::vector<Shard> read_manifests(const std::vector<std::string>& files) {
  std::vector<Shard> shards;
  for (const std::string& f : files) {
    const SweepManifest m = read_manifest(f);
    if (!m.complete) throw UsageError(f + ": this shard is not complete (its manifest says so); finish it with --resume first");
    // Without the count of input columns the outputs could not be told from inputs and checked.
    if (!m.inputs) throw UsageError(f + ": its manifest does not say how many input columns the rows have; run the shard again");
    if (!shards.empty()) {
      const SweepManifest& first = shards.front().manifest;
      if (m.sweep != first.sweep || m.cases != first.cases || m.format != first.format || m.inputs != first.inputs)
        throw UsageError(f + " belongs to another sweep than " + shards.front().file + " (scene, a file it reads, --set, cases or columns differ)" +
                         (m.rows_format ? unrecorded_format_note(first) : unrecorded_format_note(m)));
    }
    shards.push_back({f, m});
  }
  // Shards whose manifests record different formats of rows were written by different mechgraphs:
  // their cells would not be written alike. All are named at once (a cluster's reruns are costly).
  const Shard* recorded = nullptr;
  for (const Shard& s : shards)
    if (s.manifest.rows_format && !recorded) recorded = &s;
  std::string differing;
  if (recorded)
    for (const Shard& s : shards)
      if (s.manifest.rows_format && *s.manifest.rows_format != *recorded->manifest.rows_format)
        differing += (differing.empty() ? "" : ", ") + excerpt(s.file) + " (format " + std::to_string(*s.manifest.rows_format) + ")";
  if (!differing.empty())
    throw UsageError("the shards were written by different mechgraphs: " + excerpt(recorded->file) + " holds rows of format " +
                     std::to_string(*recorded->manifest.rows_format) + ", " + differing +
                     "; run the shards of one format again with the mechgraph that wrote the others");
  return shards;
}

// One shard being read: its checker and the row it is at.
struct Cursor {
  const Shard* shard;
  bool announce;  // whether to say what another tool added (once per file: not on merge's checking pass)
  LineReader reader;
  RowChecker checker;
  std::string line;
  std::size_t index = 0;  // the case of `line`
  bool failed = false;
  Cursor(const Shard& s, bool announce_marks)
      : shard(&s),
        announce(announce_marks),
        reader(s.file, max_row_bytes),
        checker({s.manifest.format, s.manifest.cases, s.manifest.shard, s.manifest.shards, s.manifest.inputs, {}}, s.file) {}
  ForeignLineMarks marks;  // what another tool added (read past, written as mechgraph writes)
  // The next line, without a byte order mark or a CR before its break; false at the end.
  bool next_line(std::string& text) {
    if (!reader.next(text)) return false;
    const ForeignLineMarks found = strip_foreign_line_marks(text, reader.number());
    if (announce && found.any() && !marks.any())
      spdlog::info("merge: {}: {}; merged as LF lines", excerpt(shard->file), foreign_line_marks_text(found));
    marks.byte_order_mark |= found.byte_order_mark;
    marks.carriage_return |= found.carriage_return;
    return true;
  }
  // The next row, checked; false at the end.
  bool advance() {
    if (!next_line(line)) return false;
    const RowChecker::Row row = checker.row(line, reader.number());
    index = row.index;
    failed = row.failed;
    return true;
  }
};

struct Counts {
  std::size_t rows = 0, failed = 0;
};

// Every row of every shard, checked, in case order to `out`; refuses (UsageError) a shard whose
// columns differ from the first's, a case in two shards, or a case in none.
Counts merge_rows(const std::vector<Shard>& shards, std::ostream& out, bool announce = true) {
  std::vector<std::unique_ptr<Cursor>> cursors;
  std::string header;           // CSV: the first shard's header line
  std::vector<std::string> keys;  // JSON Lines: the first row's keys
  std::string keys_file;
  using Entry = std::pair<std::size_t, std::size_t>;  // (case, cursor)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> next;
  for (const Shard& s : shards) {
    auto& c = *cursors.emplace_back(std::make_unique<Cursor>(s, announce));
    if (s.manifest.format == RowFormat::csv) {
      std::string line;
      if (!c.next_line(line)) throw UsageError(s.file + ": empty; a rows file starts with its header");
      c.checker.header(line, 1);
      if (header.empty()) {
        header = line;
        out << header << "\n";
      } else if (line != header) {
        throw UsageError(s.file + ": its columns differ from " + shards.front().file + "'s");
      }
    }
    if (!c.advance()) continue;
    if (s.manifest.format == RowFormat::jsonl) {
      // The keys of a shard's rows are its columns (RowChecker holds every row to its first).
      if (keys_file.empty()) {
        keys = c.checker.header_cells();
        keys_file = s.file;
      } else if (c.checker.header_cells() != keys) {
        throw UsageError(s.file + ": its rows have other keys (columns) than " + keys_file + "'s; not shards of one sweep");
      }
    }
    next.emplace(c.index, cursors.size() - 1);
  }
  const std::size_t cases = shards.front().manifest.cases;
  Counts counts;
  std::size_t expected = 0, missing_count = 0;
  std::string missing, previous_file;
  auto note_missing = [&](std::size_t from, std::size_t to) {  // cases [from, to) in no shard
    for (std::size_t c = from; c < to && missing_count < 10; ++c) missing += (missing.empty() ? "" : ", ") + std::to_string(c);
    missing_count += to - from;
  };
  while (!next.empty()) {
    const auto [index, k] = next.top();
    next.pop();
    Cursor& c = *cursors[k];
    if (counts.rows > 0 && index + 1 == expected)
      throw UsageError("case " + std::to_string(index) + " is in both " + previous_file + " and " + c.shard->file);
    if (index > expected) note_missing(expected, index);
    expected = index + 1;
    previous_file = c.shard->file;
    out << c.line << "\n";
    ++counts.rows;
    if (c.failed) ++counts.failed;
    if (c.advance()) next.emplace(c.index, k);
  }
  note_missing(expected, cases);
  if (missing_count)
    throw UsageError("the files hold " + std::to_string(counts.rows) + " of the sweep's " + std::to_string(cases) +
                     " cases; missing: " + missing + (missing_count > 10 ? ", ..." : "") + " (is a shard absent?)");
  return counts;
}

// A stream that keeps nothing: merge's checking pass.
class NullBuffer final : public std::streambuf {
 protected:
  int_type overflow(int_type c) override { return traits_type::not_eof(c); }
  std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
};

// Every shard is open at once: as many descriptors as the process may have, raised to the hard limit.
void allow_open_files(std::size_t files) {
  rlimit limit{};
  if (::getrlimit(RLIMIT_NOFILE, &limit) != 0) return;
  const rlim_t wanted = static_cast<rlim_t>(files) + 32;
  if (limit.rlim_cur >= wanted) return;
  limit.rlim_cur = limit.rlim_max == RLIM_INFINITY ? wanted : std::min(wanted, limit.rlim_max);
  ::setrlimit(RLIMIT_NOFILE, &limit);
  if (::getrlimit(RLIMIT_NOFILE, &limit) == 0 && limit.rlim_cur < wanted)
    throw UsageError("merge reads its " + std::to_string(files) + " files at once, and this process may open " +
                     std::to_string(limit.rlim_cur) + " (ulimit -n); merge them in groups, then merge the results");
}

}  // namespace

int merge_command(const GlobalOptions&, const std::vector<std::string>& args) {
  po::options_description visible("merge options");
  visible.add_options()("help,h", "this text")("out", po::value<std::string>(), "write the merged rows to FILE (else stdout)")(
      "force", "replace an existing FILE that mechgraph wrote (its manifest FILE.json says so)");
  po::options_description all;
  all.add(visible).add_options()("files", po::value<std::vector<std::string>>(), "shard files");
  po::positional_options_description positional;
  positional.add("files", -1);
  po::variables_map vm;
  if (!parse_options(args, visible, all, positional, vm, "mechgraph merge FILE... [--out FILE]   (e.g. mechgraph merge part-*.csv --out all.csv)"))
    return ok;
  if (!vm.count("files"))
    throw UsageError("no rows files to merge: name the shards' files, e.g. mechgraph merge part-*.csv --out all.csv");

  // The output is locked and checked before the shards are read: a second merge is refused at once.
  std::optional<OutputLock> lock;
  const bool force = vm.count("force") > 0;
  if (vm.count("out")) {
    const fs::path out = vm["out"].as<std::string>();
    prepare_output_file(out, "--out");
    lock.emplace(out);
    if (kind_of(out) != "absent") {
      if (kind_of(out) == "a regular file" && !force) throw UsageError(out.string() + " exists; use --force to replace it");
      refuse_unless_ours(out, has_sweep_manifest(out), "--out");
    }
    if (kind_of(manifest_path(out)) != "absent" && !has_sweep_manifest(out))
      throw UsageError(manifest_path(out).string() + " is not a sweep manifest mechgraph wrote: it is left alone; choose another --out");
  }

  const auto files = vm["files"].as<std::vector<std::string>>();
  const std::vector<Shard> shards = read_manifests(files);
  allow_open_files(shards.size());
  Counts counts;
  if (!vm.count("out")) {
    NullBuffer nothing;
    std::ostream check(&nothing);
    merge_rows(shards, check, false);  // everything refused before a byte reaches stdout
    counts = merge_rows(shards, std::cout);
    std::cout.flush();
    if (!std::cout) throw IoError("standard output: cannot write");
  } else {
    const fs::path out = vm["out"].as<std::string>();
    write_file_whole(out, force, [&](std::ostream& os) { counts = merge_rows(shards, os); });
    SweepManifest m = shards.front().manifest;
    for (const Shard& s : shards)  // the format the shards record (they agree), if any records one
      if (s.manifest.rows_format) m.rows_format = s.manifest.rows_format;
    m.shard = 0;
    m.shards = 1;
    m.complete = true;
    m.rows = counts.rows;
    m.failed = counts.failed;
    write_manifest(out, m);
  }
  spdlog::info("merge: {} cases from {} files, each once", counts.rows, files.size());
  return ok;
}

}  // namespace mechgraph::cli
