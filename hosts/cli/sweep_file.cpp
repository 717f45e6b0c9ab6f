#include "sweep_file.hpp"

#include "cli.hpp"
#include "line_reader.hpp"
#include "output_file.hpp"

#include <mechgraph/csv.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/json_writer.hpp>
#include <mechgraph/sweep/case_table.hpp>

#include <yaml-cpp/yaml.h>

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <sstream>

namespace mechgraph::cli {
namespace fs = std::filesystem;
namespace {

// A whole number field of a manifest, at most `limit`: digits only (no sign, no exponent), so a
// "-1" or "1e15" cannot wrap or slip past the limit.
std::size_t count_field(const YAML::Node& node, const std::string& key, std::size_t limit) {
  const std::string text = node.as<std::string>();
  if (text.empty() || text.size() > 19 || !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
    throw UsageError("'" + key + "' is '" + excerpt(text, 40) + "', not a whole number");
  const std::size_t value = std::stoull(text);
  if (value > limit) throw UsageError("'" + key + "' is " + text + ", more than " + std::to_string(limit));
  return value;
}

}  // namespace

fs::path manifest_path(const fs::path& file) { return fs::path(file.string() + ".json"); }

SweepManifest read_manifest(const fs::path& file) { return read_manifest_checked(file); }

SweepManifest read_manifest_checked(const fs::path& file) {
  const fs::path path = manifest_path(file);
  if (kind_of(path) == "absent")
    throw UsageError(file.string() + ": no manifest " + path.string() + " beside it (was it written by mechgraph sweep --out?)");
  const std::string text = read_user_file(path, max_manifest_bytes, "sweep manifest");
  try {
    const YAML::Node j = YAML::Load(text);
    if (!j.IsMap()) throw UsageError("not a JSON object");
    SweepManifest m;
    m.sweep = j["sweep"].as<std::string>();
    m.cases = count_field(j["cases"], "cases", max_sweep_cases);
    m.shards = count_field(j["shard"][1], "shard[1]", 1000000);
    m.shard = count_field(j["shard"][0], "shard[0]", 1000000);
    if (m.shards == 0 || m.shard >= m.shards) throw UsageError("the shard is not I/N with 0 <= I < N");
    m.complete = j["complete"].as<bool>();
    m.rows = count_field(j["rows"], "rows", m.cases);
    m.failed = count_field(j["failed"], "failed", m.rows);
    m.scene = j["scene"].as<std::string>();
    m.origin = j["origin"].as<std::string>();
    const std::string format = j["format"].as<std::string>();
    if (format != "csv" && format != "jsonl") throw UsageError("the format is neither csv nor jsonl");
    m.format = format == "jsonl" ? RowFormat::jsonl : RowFormat::csv;
    if (j["inputs"]) m.inputs = count_field(j["inputs"], "inputs", 100000);
    m.rows_format.reset();
    if (j["rows_format"]) {
      m.rows_format = count_field(j["rows_format"], "rows_format", 1000000);
      if (*m.rows_format == 0) throw UsageError("'rows_format' is 0; formats count from 1");
    }
    return m;
  } catch (const YAML::Exception& e) {
    throw UsageError(path.string() + ": not a sweep manifest (" + excerpt(e.what()) + ")");
  } catch (const UsageError& e) {
    throw UsageError(path.string() + ": not a sweep manifest: " + e.what());
  }
}

void require_rows_format(const SweepManifest& m, const std::string& file, const std::string& remedy) {
  if (!m.rows_format || *m.rows_format == rows_format_written) return;
  const std::string by = *m.rows_format < rows_format_written ? "an older mechgraph" : "a newer mechgraph";
  throw UsageError(excerpt(file) + ": its rows were written by " + by + " (rows format " + std::to_string(*m.rows_format) +
                   ", its manifest says; this one writes format " + std::to_string(rows_format_written) +
                   "): the formats write a case's cells and fingerprint differently, so these rows cannot be matched " +
                   "to this program's; " + remedy);
}

std::string unrecorded_format_note(const SweepManifest& m) {
  if (m.rows_format) return {};
  return " (its manifest does not record the rows' format, as mechgraph before December 2026 wrote it: a mechgraph of "
         "before then may have written grid points and generated values otherwise than this one does; if so, use that "
         "mechgraph, or run the sweep again with this one)";
}

bool has_sweep_manifest(const fs::path& file) {
  try {
    read_manifest_checked(file);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

void write_manifest(const fs::path& file, const SweepManifest& m) {
  const fs::path path = manifest_path(file);
  const std::string kind = kind_of(path);
  if (kind != "absent" && (kind != "a regular file" || !has_sweep_manifest(file)))
    throw UsageError(path.string() + " is " + (kind == "a regular file" ? std::string("not a sweep manifest") : kind) +
                     ": mechgraph did not write it and leaves it alone; choose another --out or remove it");
  write_file_whole(path, true, [&](std::ostream& os) {
    JsonWriter json(os);
    json.begin_object();
    json.key("sweep").value(m.sweep);
    json.key("cases").value(static_cast<long>(m.cases));
    json.key("shard").begin_array().value(static_cast<long>(m.shard)).value(static_cast<long>(m.shards)).end_array();
    json.key("complete").value(m.complete);
    json.key("rows").value(static_cast<long>(m.rows));
    json.key("failed").value(static_cast<long>(m.failed));
    json.key("scene").value(m.scene);
    json.key("origin").value(m.origin);
    json.key("format").value(m.format == RowFormat::jsonl ? "jsonl" : "csv");
    if (m.inputs) json.key("inputs").value(static_cast<long>(*m.inputs));
    if (m.rows_format) json.key("rows_format").value(static_cast<long>(*m.rows_format));
    json.end_object();
    os << "\n";
  });
}

SweepFile::SweepFile(const fs::path& out, SweepManifest manifest, bool resume, bool force, const RowRules& rules)
    : out_(out), manifest_(std::move(manifest)) {
  if (out_.empty()) return;
  prepare_output_file(out_, "--out");  // `--out DIR/` refused before its lock is made; a/b/ made
  lock_.emplace(out_);  // before anything is read or written: one writer per FILE
  part_ = fs::path(out_.string() + ".part");
  if (resume && kind_of(part_) != "absent") resume_part(rules);
  else start_fresh(resume, force);
  manifest_.complete = false;
  write_manifest(out_, manifest_);
  if (!file_) file_ = create_exclusive(part_);
}

namespace {

// Whether a manifest read back records the rows of the sweep `m` describes: its fingerprint and shard.
bool same_sweep(const SweepManifest& before, const SweepManifest& m) {
  return before.sweep == m.sweep && before.shard == m.shard && before.shards == m.shards;
}

// Whether `tail`, the text after the last line break of FILE.part, can be the start of a line this
// sweep writes, cut by a kill: a prefix of the header, of a CSV row (its case number first) or of
// a JSON Lines row.
bool plausible_cut_line(std::string_view tail, RowFormat format, bool header_next) {
  if (tail.empty()) return true;
  const auto starts = [&](std::string_view start) {
    return tail.size() <= start.size() ? start.substr(0, tail.size()) == tail : tail.substr(0, start.size()) == start;
  };
  if (format == RowFormat::jsonl) return starts("{\"case\":");
  if (header_next) return starts("case,");
  return tail[0] >= '0' && tail[0] <= '9';
}

}  // namespace

// --resume: every whole line in FILE.part is checked first; only then is a half-written last line
// cut (a file that is not this sweep's rows is refused untouched).
void SweepFile::resume_part(const RowRules& rules) {
  const SweepManifest before = read_manifest(out_);
  require_rows_format(before, part_.string(),
                      "finish the sweep with the mechgraph that began it, or start over with --force");
  if (!same_sweep(before, manifest_))
    throw UsageError(part_.string() + " holds rows of another sweep (scene, a file it reads, --set, cases, outputs or shard "
                     "differ); remove it or use --force to start over" + unrecorded_format_note(before));
  file_ = open_existing_regular(part_);
  // A line at a time (memory: one row, whatever the file's size), the cut last line kept apart.
  LineReader reader(file_.get(), part_, max_row_bytes, LineReader::LastLine::keep);
  RowChecker checker(rules, part_.string());
  std::string line;
  std::size_t number = 1;
  for (; reader.next(line); ++number) {
    // Appended to as it is: CR LF line ends would be mixed with the LF ones this sweep writes.
    if (const ForeignLineMarks marks = strip_foreign_line_marks(line, number); marks.any())
      throw UsageError(excerpt(part_.string()) + ":" + std::to_string(number) + ": the line " + foreign_line_marks_text(marks) +
                       "; --resume appends to the file as it is and would mix them: convert it back (dos2unix " +
                       excerpt(part_.string()) + ") and resume, or start over with --force");
    if (number == 1 && manifest_.format == RowFormat::csv) {
      checker.header(line, number);
      resumed_header_ = checker.header_cells();
      continue;
    }
    RowChecker::Row row{};
    try {
      row = checker.row(line, number);
    } catch (const UsageError& e) {
      throw UsageError(std::string(e.what()) + unrecorded_format_note(before));
    }
    resumed_cases_.push_back(row.index);
    if (row.failed) ++resumed_failed_;
  }
  const std::string& tail = reader.unterminated();
  const std::uint64_t keep = reader.whole_bytes();
  if (!plausible_cut_line(tail, manifest_.format, manifest_.format == RowFormat::csv && number == 1))
    throw UsageError(excerpt(part_.string()) + ":" + std::to_string(number) + ": the unfinished last line '" + excerpt(tail, 40) +
                     "' is not the start of a row mechgraph writes; refused (edited or damaged?), the file is left as it is");
  if (!tail.empty() && ::ftruncate(file_.get(), static_cast<off_t>(keep)) != 0) io_failure("cut the half-written last line of", part_, errno);
}

// A fresh start: FILE and FILE.part are removed first, but only when mechgraph wrote them.
void SweepFile::start_fresh(bool resume, bool force) {
  const bool ours = has_sweep_manifest(out_);
  const std::string out_kind = kind_of(out_), part_kind = kind_of(part_);
  if (out_kind != "absent") {
    if (out_kind == "a regular file" && !force) {
      if (resume && ours) {
        // Complete, but of this sweep? Another's (another design, --set, scene) has nothing to resume either.
        const SweepManifest before = read_manifest(out_);
        if (!same_sweep(before, manifest_))
          throw UsageError(out_.string() + " holds the complete rows of another sweep (" + excerpt(before.origin, 160) +
                           "; the scene, a file it reads, --set, cases, outputs or shard differ): nothing of this one to resume; "
                           "--force replaces them, or write this sweep to another --out");
      }
      if (resume) throw UsageError(out_.string() + " is complete already; nothing to resume (--force runs it again)");
      throw UsageError(out_.string() + " exists; use --force to replace it");
    }
    refuse_unless_ours(out_, ours, "--out");
  }
  if (part_kind != "absent") {
    if (part_kind == "a regular file" && !force)
      throw UsageError(part_.string() + " holds an unfinished sweep: --resume goes on with it, --force starts over");
    refuse_unless_ours(part_, ours, "--out's unfinished rows");
  }
  for (const fs::path& p : {out_, part_})
    if (::unlink(p.c_str()) != 0 && errno != ENOENT) io_failure("remove", p, errno);
}

SweepFile::~SweepFile() = default;

void SweepFile::write(const std::string& text) {
  if (file_) {
    write_all(file_.get(), text, part_);
    return;
  }
  if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() || std::fflush(stdout) != 0)
    io_failure("write to", "standard output", errno);
}

void SweepFile::finish(bool complete, std::size_t rows, std::size_t failed) {
  if (!file_) return;
  // On the disk before FILE.part takes FILE's name: a crash after the rename never leaves a FILE
  // whose last rows were still in the page cache.
  if (::fsync(file_.get()) != 0) io_failure("write", part_, errno);
  if (::close(file_.release()) != 0) io_failure("close", part_, errno);
  manifest_.rows = rows;
  manifest_.failed = failed;
  if (complete) {
    if (std::rename(part_.c_str(), out_.c_str()) != 0) io_failure("rename to " + out_.string() + " the file", part_, errno);
    manifest_.complete = true;
  }
  write_manifest(out_, manifest_);
}

}  // namespace mechgraph::cli
