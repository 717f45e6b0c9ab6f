#include "sweep_file.hpp"

#include "cli.hpp"

#include <mechgraph/csv.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/json_writer.hpp>

#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace mechgraph::cli {
namespace fs = std::filesystem;
namespace {

[[noreturn]] void io_failure(const fs::path& p, const std::string& what) {
  throw IoError(p.string() + ": " + what + ": " + std::strerror(errno));
}

// The case number at the start of a row: "12,..." in CSV, {"case":12,...} in JSON Lines.
std::optional<std::size_t> case_of(const std::string& line, RowFormat format) {
  std::size_t pos = 0;
  if (format == RowFormat::jsonl) {
    const std::string key = "{\"case\":";
    if (line.rfind(key, 0) != 0) return std::nullopt;
    pos = key.size();
  }
  std::size_t value = 0, digits = 0;
  for (; pos < line.size() && std::isdigit(static_cast<unsigned char>(line[pos])); ++pos, ++digits) value = value * 10 + (line[pos] - '0');
  if (!digits) return std::nullopt;
  return value;
}

bool failed_row(const std::string& line, RowFormat format) {
  if (format == RowFormat::jsonl) return line.find("\"error\":null}") == std::string::npos;
  try {
    const auto fields = split_csv_line(line);
    return fields.size() >= 2 && fields[fields.size() - 2] != "0";
  } catch (const std::invalid_argument&) {
    return true;
  }
}

}  // namespace

fs::path manifest_path(const fs::path& file) { return fs::path(file.string() + ".json"); }

SweepManifest read_manifest(const fs::path& file) {
  const fs::path path = manifest_path(file);
  if (!fs::exists(path)) throw UsageError(file.string() + ": no manifest " + path.string() + " beside it (was it written by mechgraph sweep --out?)");
  try {
    const YAML::Node j = YAML::LoadFile(path.string());
    SweepManifest m;
    m.sweep = j["sweep"].as<std::string>();
    m.cases = j["cases"].as<std::size_t>();
    m.shard = j["shard"][0].as<std::size_t>();
    m.shards = j["shard"][1].as<std::size_t>();
    m.complete = j["complete"].as<bool>();
    m.rows = j["rows"].as<std::size_t>();
    m.failed = j["failed"].as<std::size_t>();
    m.scene = j["scene"].as<std::string>();
    m.origin = j["origin"].as<std::string>();
    m.format = j["format"].as<std::string>() == "jsonl" ? RowFormat::jsonl : RowFormat::csv;
    return m;
  } catch (const YAML::Exception& e) {
    throw UsageError(path.string() + ": not a sweep manifest (" + e.what() + ")");
  }
}

SweepFile::SweepFile(const fs::path& out, SweepManifest manifest, bool resume, bool force)
    : out_(out), manifest_(std::move(manifest)) {
  if (out_.empty()) return;
  part_ = fs::path(out_.string() + ".part");
  if (resume && fs::exists(part_)) {
    const SweepManifest before = read_manifest(out_);
    if (before.sweep != manifest_.sweep || before.shard != manifest_.shard || before.shards != manifest_.shards)
      throw UsageError(part_.string() + " holds rows of another sweep (scene, --set, cases, outputs or shard differ); "
                       "remove it or use --force to start over");
    // Cut a line a kill left half-written, then read what is there.
    std::string text;
    {
      std::ifstream in(part_, std::ios::binary);
      std::ostringstream all;
      all << in.rdbuf();
      text = all.str();
    }
    const std::size_t keep = text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1;
    if (keep != text.size()) fs::resize_file(part_, keep);
    std::istringstream lines(text.substr(0, keep));
    std::string line;
    bool first = true;
    while (std::getline(lines, line)) {
      if (first && manifest_.format == RowFormat::csv) {
        resumed_header_ = split_csv_line(line);
        first = false;
        continue;
      }
      first = false;
      const auto c = case_of(line, manifest_.format);
      if (!c) throw UsageError(part_.string() + ": a row without a case number; the file is not a sweep's");
      resumed_cases_.push_back(*c);
      if (failed_row(line, manifest_.format)) ++resumed_failed_;
    }
  } else {
    if (fs::exists(out_) && !force) {
      if (resume) throw UsageError(out_.string() + " is complete already; nothing to resume (--force runs it again)");
      throw UsageError(out_.string() + " exists; use --force to replace it");
    }
    if (fs::exists(part_) && !force)
      throw UsageError(part_.string() + " holds an unfinished sweep: --resume goes on with it, --force starts over");
    std::error_code ignored;
    fs::remove(out_, ignored);
    fs::remove(part_, ignored);
  }
  manifest_.complete = false;
  write_manifest();
  file_ = std::fopen(part_.c_str(), "ab");
  if (!file_) io_failure(part_, "cannot open for writing");
}

SweepFile::~SweepFile() {
  if (file_) std::fclose(file_);
}

void SweepFile::write(const std::string& text) {
  std::FILE* f = file_ ? file_ : stdout;
  if (std::fwrite(text.data(), 1, text.size(), f) != text.size() || std::fflush(f) != 0)
    io_failure(file_ ? part_ : fs::path("standard output"), "cannot write");
}

void SweepFile::finish(bool complete, std::size_t rows, std::size_t failed) {
  if (!file_) return;
  if (std::fclose(file_) != 0) {
    file_ = nullptr;
    io_failure(part_, "cannot close");
  }
  file_ = nullptr;
  manifest_.rows = rows;
  manifest_.failed = failed;
  if (complete) {
    std::error_code error;
    fs::rename(part_, out_, error);
    if (error) throw IoError(part_.string() + ": cannot rename to " + out_.string() + ": " + error.message());
    manifest_.complete = true;
  }
  write_manifest();
}

void SweepFile::write_manifest() {
  const fs::path path = manifest_path(out_), staging = fs::path(path.string() + ".tmp");
  {
    std::ofstream os(staging);
    JsonWriter json(os);
    json.begin_object();
    json.key("sweep").value(manifest_.sweep);
    json.key("cases").value(static_cast<long>(manifest_.cases));
    json.key("shard").begin_array().value(static_cast<long>(manifest_.shard)).value(static_cast<long>(manifest_.shards)).end_array();
    json.key("complete").value(manifest_.complete);
    json.key("rows").value(static_cast<long>(manifest_.rows));
    json.key("failed").value(static_cast<long>(manifest_.failed));
    json.key("scene").value(manifest_.scene);
    json.key("origin").value(manifest_.origin);
    json.key("format").value(manifest_.format == RowFormat::jsonl ? "jsonl" : "csv");
    json.end_object();
    os << "\n";
    os.close();
    if (!os) io_failure(staging, "cannot write");
  }
  std::error_code error;
  fs::rename(staging, path, error);
  if (error) throw IoError(staging.string() + ": cannot rename to " + path.string() + ": " + error.message());
}

}  // namespace mechgraph::cli
