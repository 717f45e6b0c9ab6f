#pragma once
// What an uncertainty study answers, from the values of its cases: per output the moments,
// quantiles, histogram, capability against its spec limits and Sobol' indices; per event its
// probability. Values are taken in each output's shown unit (the unit of its column in a sweep's
// rows), so a study computed in process and one computed from the rows of its shards (written
// exactly, read back to the same doubles) give the same bits. The JSON gives every number in SI.
#include <atomic>
#include <mechgraph/dimension.hpp>
#include <mechgraph/json_writer.hpp>
#include <mechgraph/sweep/sweep_runner.hpp>
#include <mechgraph/uncertainty/study_spec.hpp>
#include <mechgraph/uncertainty/study_statistics.hpp>

#include <functional>
#include <ostream>
#include <optional>
#include <string>
#include <vector>

namespace mechgraph {

struct StudyColumn {
  std::string label;  // "node.port"
  std::string unit;   // shown unit ("" = SI)
  double scale = 1.0, offset = 0.0;  // si = (shown + offset) * scale
  Dimension dimension;
  std::string shown;  // the unit as the sweep's rows and the report show it, with an angle's frame tag: "deg (shaft)"
};

/// The evaluated design: per output, per case (in case order) its value in the shown unit (NaN
/// where the case failed); per case its failure class.
struct StudyData {
  std::vector<StudyColumn> outputs;
  std::vector<std::vector<double>> values;  // [output][case]
  std::vector<CaseFailure> failures;        // [case]
  /// The failed case of the lowest number and its message (as the sweep's error column gives it),
  /// for the log: a study whose cases fail says why.
  std::optional<std::size_t> first_failed;
  std::string first_error;
  /// Case i failed (failure class and message): kept as the first when it is the lowest so far.
  void record_failure(std::size_t i, CaseFailure failure, const std::string& error) {
    failures[i] = failure;
    if (!first_failed || i < *first_failed) {
      first_failed = i;
      first_error = error;
    }
  }
};

struct OutputAnswer {
  StudyColumn column;
  Moments moments;
  std::size_t failed = 0;  // of the statistical samples, cases with no value
  std::vector<QuantileEstimate> quantiles;
  Histogram histogram;
  const SpecLimits* limits = nullptr;
  std::optional<double> lower, upper;  // the limits in the shown unit
  std::optional<Capability> capability;
  std::optional<SobolIndices> sobol;
};

struct EventAnswer {
  const StudyEvent* event = nullptr;
  Proportion probability;
  std::size_t undecided = 0;  // an output event: cases that failed (no value to compare)
};

struct StudyAnswers {
  std::size_t cases = 0, samples = 0, failed = 0;  // samples: the statistical ones (A and B rows with sensitivity)
  std::vector<OutputAnswer> outputs;
  std::vector<EventAnswer> events;
};

/// Throws SceneError when a limit or an event names an output the study does not have (at its
/// file:line:column, with the valid names).
/// `threads`: for the bootstrap; the answers do not depend on it.
/// The confidence level as a percentage for a label: "95", "99.9", "99.99" (ten significant
/// digits at most, no trailing zeros; a whole percentage would print 0.999 as 100).
std::string confidence_percent(double confidence);

/// Checks, before any case runs, that every spec limit and every event threshold names one of the
/// study's outputs and is written in that output's dimension: a limit in mm on a mass, or a bare
/// number on a dimensional output, is refused (a bare number would be read in SI, silently).
/// Throws SceneError at the limit's or event's file:line:column.
void check_study_outputs(const StudySpec& spec, const std::vector<StudyColumn>& outputs);

/// `stop` (Ctrl-C, SIGTERM) ends the analysis early: the answers are then not to be used.
StudyAnswers analyse_study(const StudySpec& spec, const StudyData& data, unsigned threads = 1, const std::atomic<bool>* stop = nullptr);

/// The answers as one JSON object (SI), the study's settings and parameters with them; `more`,
/// when given, writes further members before the object closes (the command's provenance).
void write_study_json(JsonWriter& out, const StudySpec& spec, const StudyAnswers& answers,
                      const std::function<void(JsonWriter&)>& more = {});

}  // namespace mechgraph
