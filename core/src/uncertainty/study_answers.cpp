#include <mechgraph/uncertainty/study_answers.hpp>

#include <mechgraph/did_you_mean.hpp>
#include <mechgraph/error_subject.hpp>
#include <mechgraph/errors.hpp>

#include <mechgraph/chunked_work.hpp>
#include <mechgraph/large_arrays.hpp>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <exception>

namespace mechgraph {
namespace {

std::size_t output_index(const std::vector<StudyColumn>& outputs, const std::string& label, const SourceLocation& where) {
  std::vector<std::string> names;
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    if (outputs[k].label == label) return k;
    names.push_back(outputs[k].label);
  }
  throw_scene_error_at(where, unknown_name_message("study output", label, names) +
                   " (a study reads the scene's scalar outputs; add it to outputs:)");
}

std::size_t output_index(const StudyData& data, const std::string& label, const SourceLocation& where) {
  return output_index(data.outputs, label, where);
}

// A limit or threshold written in another dimension than its output's, or bare on a dimensional
// output: the message says what the output is and the unit its values are shown in.
void check_dimension(const Dimension& written, const StudyColumn& output, const SourceLocation& where, const std::string& what) {
  if (written == output.dimension) return;
  const std::string shown_in = !output.shown.empty() ? output.shown : output.unit.empty() ? output.dimension.si_unit() : output.unit;
  if (written.dimensionless())
    throw_scene_error_at(where, what + " is a bare number, but '" + output.label + "' is " + output.dimension.describe() +
                     ": write the unit (its values are shown in " + shown_in + ")");
  throw_scene_error_at(where, what + " is " + written.describe() + ", but '" + output.label + "' is " +
                   output.dimension.describe() + " (shown in " + shown_in + ")");
}

double shown(double si, const StudyColumn& c) { return si / c.scale - c.offset; }
double to_si(double v, const StudyColumn& c) { return (v + c.offset) * c.scale; }

std::string plain(double x) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, end);
}

// A bare number against a plain-number output shown in a scaled unit (a share in %, a rate in
// ppm) is read as a plain number, as everywhere in a scene: 30 is 3000 %. Valid, so not refused,
// but an easy slip for "30 %": said, with both readings and how to write the other.
void warn_bare_against_scaled(double value, const StudyColumn& output, const SourceLocation& where, const std::string& what) {
  if (!output.dimension.dimensionless() || (output.scale == 1.0 && output.offset == 0.0) || output.unit.empty()) return;
  spdlog::warn("{}{} is the bare number {}, read as a plain number: {} {} as '{}' is shown; if {} {} was meant, write '{} {}'",
               where.str(), what, plain(value), plain(shown(value, output)), output.unit, output.label, plain(value), output.unit,
               plain(value), output.unit);
}

// The answer of output o alone (moments, quantiles, limits, histogram) and, for a sensitivity
// study, its Saltelli samples: the base samples whose d + 2 cases all have a value.
void answer_output(const StudySpec& spec, const StudyData& data, const std::vector<std::size_t>& statistical, std::size_t o,
                   OutputAnswer& a, SobolSamples* sobol, std::vector<std::size_t>* kept) {
  const std::size_t d = spec.parameters.size();
  const std::size_t per_sample = spec.sensitivity ? d + 2 : 1;
  const std::size_t cases = data.failures.size();

  a.column = data.outputs[o];
  const std::vector<double>& column = data.values[o];
  std::vector<double> values;
  reserve_large(values, statistical.size());
  for (std::size_t k : statistical)
    if (std::isfinite(column[k])) values.push_back(column[k]);
  a.failed = statistical.size() - values.size();
  a.moments = moments(values, spec.confidence);  // in case order, before the values are sorted
  // Sorted in place for the quantiles: what reads the values after (the capability's and the
  // histogram's counts) does not depend on their order, and no copy is held beside them.
  std::sort(values.begin(), values.end());
  if (!values.empty())
    for (double level : spec.quantiles) a.quantiles.push_back(quantile(values, level, spec.confidence));
  for (const SpecLimits& l : spec.limits)
    if (l.output == a.column.label) a.limits = &l;
  double low = values.empty() ? 0.0 : values.front(), high = values.empty() ? 0.0 : values.back();
  if (a.limits) {
    if (a.limits->lower) a.lower = shown(*a.limits->lower, a.column);
    if (a.limits->upper) a.upper = shown(*a.limits->upper, a.column);
    // The histogram shows the limits beside the values.
    if (a.lower) low = std::min(low, *a.lower), high = std::max(high, *a.lower);
    if (a.upper) low = std::min(low, *a.upper), high = std::max(high, *a.upper);
    if (!values.empty()) a.capability = capability(values, a.moments, a.lower, a.upper, spec.confidence, a.failed);
  }
  a.histogram = histogram(values, spec.bins, low, high);
  if (spec.sensitivity) {
    SobolSamples& f = *sobol;
    const std::size_t base_samples = cases / per_sample;
    kept->reserve(base_samples);
    reserve_large(f.f_a, base_samples);
    reserve_large(f.f_b, base_samples);
    f.f_ab.resize(d);
    for (std::vector<double>& f_j : f.f_ab) reserve_large(f_j, base_samples);
    for (std::size_t i = 0; i * per_sample < cases; ++i) {
      const std::size_t k = i * per_sample;
      bool whole = k + per_sample <= cases;
      for (std::size_t r = 0; whole && r < per_sample; ++r) whole = std::isfinite(column[k + r]);
      if (!whole) continue;
      kept->push_back(i);
      f.f_a.push_back(column[k]);
      f.f_b.push_back(column[k + 1]);
      for (std::size_t j = 0; j < d; ++j) f.f_ab[j].push_back(column[k + 2 + j]);
    }
  }
}

}  // namespace

std::string confidence_percent(double confidence) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, 100.0 * confidence, std::chars_format::general, 10);
  return std::string(buffer, end);
}

void check_study_outputs(const StudySpec& spec, const std::vector<StudyColumn>& outputs) {
  for (const SpecLimits& l : spec.limits) {
    const StudyColumn& output = outputs[output_index(outputs, l.output, l.where)];
    check_dimension(l.dimension, output, l.where, "the limits of '" + l.output + "'");
    if (l.lower && l.lower_bare) warn_bare_against_scaled(*l.lower, output, l.where, "the lower limit of '" + l.output + "'");
    if (l.upper && l.upper_bare) warn_bare_against_scaled(*l.upper, output, l.where, "the upper limit of '" + l.output + "'");
  }
  for (const StudyEvent& e : spec.events)
    if (e.kind != StudyEvent::Kind::failure) {
      const StudyColumn& output = outputs[output_index(outputs, e.output, e.where)];
      check_dimension(e.dimension, output, e.where, "the threshold of event '" + e.name + "'");
      if (e.bare) warn_bare_against_scaled(e.threshold, output, e.where, "the threshold of event '" + e.name + "'");
    }
}

StudyAnswers analyse_study(const StudySpec& spec, const StudyData& data, unsigned threads, const std::atomic<bool>* stop) {
  StudyAnswers answers;
  const std::size_t d = spec.parameters.size();
  const std::size_t per_sample = spec.sensitivity ? d + 2 : 1;
  answers.cases = data.failures.size();
  for (CaseFailure f : data.failures) answers.failed += f != CaseFailure::none;
  // The statistical samples: every case, or the A and B rows of Saltelli's design.
  std::vector<std::size_t> statistical;
  statistical.reserve(spec.sensitivity ? 2 * (answers.cases / per_sample) : answers.cases);  // as the budget counts it
  for (std::size_t k = 0; k < answers.cases; ++k)
    if (k % per_sample < (spec.sensitivity ? 2 : 1)) statistical.push_back(k);
  answers.samples = statistical.size();
  for (const SpecLimits& l : spec.limits) output_index(data, l.output, l.where);  // every limit names a studied output

  std::vector<SobolSamples> sobol_samples(spec.sensitivity ? data.outputs.size() : 0);
  std::vector<std::vector<std::size_t>> sobol_kept(sobol_samples.size());  // the base samples each output kept
  // The outputs are independent: one a chunk, on the study's threads, each answer in its own slot;
  // an error is rethrown for the first output that had one, whatever the threads.
  answers.outputs.resize(data.outputs.size());
  std::vector<std::exception_ptr> errors(data.outputs.size());
  run_chunks(data.outputs.size(), threads, [] { return 0; }, [&](int, std::size_t o) {
    try {
      answer_output(spec, data, statistical, o, answers.outputs[o], spec.sensitivity ? &sobol_samples[o] : nullptr,
                    spec.sensitivity ? &sobol_kept[o] : nullptr);
    } catch (...) {
      errors[o] = std::current_exception();
    }
  });
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  if (spec.sensitivity) {
    // The outputs that kept the same base samples share their resamples (the usual case: all).
    std::vector<char> done(data.outputs.size(), 0);
    for (std::size_t o = 0; o < data.outputs.size(); ++o) {
      if (done[o]) continue;
      std::vector<std::size_t> group;
      for (std::size_t p = o; p < data.outputs.size(); ++p)
        if (!done[p] && sobol_kept[p] == sobol_kept[o]) group.push_back(p), done[p] = 1;
      std::vector<const SobolSamples*> samples;
      for (std::size_t p : group) samples.push_back(&sobol_samples[p]);
      std::vector<SobolIndices> indices = sobol_indices(samples, spec.bootstrap, spec.confidence, spec.seed, threads, stop);
      if (stop && stop->load(std::memory_order_relaxed)) return answers;
      for (std::size_t g = 0; g < group.size(); ++g) {
        // An output that does not vary over the samples has no indices: V_j / V is 0 / 0 there, and
        // a 0 with an interval [0, 0] would read as "no parameter matters" (its variance says 0).
        if (!(indices[g].variance > 0)) indices[g].indices.clear();
        answers.outputs[group[g]].sobol = std::move(indices[g]);
      }
      for (std::size_t p : group) sobol_samples[p] = {};  // freed as soon as used
    }
  }
  for (const StudyEvent& e : spec.events) {
    EventAnswer a;
    a.event = &e;
    std::size_t hits = 0, trials = 0;
    if (e.kind == StudyEvent::Kind::failure) {
      for (std::size_t k : statistical) {
        const CaseFailure f = data.failures[k];
        hits += e.failure == StudyEvent::Failure::any ? f != CaseFailure::none
                : e.failure == StudyEvent::Failure::scene ? f == CaseFailure::scene
                                                          : f == CaseFailure::evaluation;
      }
      trials = statistical.size();
    } else {
      const std::size_t o = output_index(data, e.output, e.where);
      const double threshold = shown(e.threshold, data.outputs[o]);
      for (std::size_t k : statistical) {
        const double v = data.values[o][k];
        if (!std::isfinite(v)) {
          ++a.undecided;
          continue;
        }
        ++trials;
        hits += e.kind == StudyEvent::Kind::above ? v > threshold : v < threshold;
      }
    }
    a.probability = proportion(hits, trials, spec.confidence);
    answers.events.push_back(a);
  }
  return answers;
}

namespace {

void write_interval(JsonWriter& out, const Interval& i, const StudyColumn* c) {
  out.begin_array();
  for (const std::optional<double>& end : {i.lower, i.upper}) {
    if (end) out.value(c ? to_si(*end, *c) : *end);
    else out.null();
  }
  out.end_array();
}

// A proportion, with the counts that go with it where given (a spec's cases below and above, an
// event's cases without a value): what the terminal prints, the files carry.
void write_proportion(JsonWriter& out, const Proportion& p, const std::function<void(JsonWriter&)>& counts = {}) {
  out.begin_object();
  out.key("events").value(static_cast<long>(p.events)).key("trials").value(static_cast<long>(p.trials));
  if (counts) counts(out);
  out.key("estimate").value(p.estimate);
  out.key("wilson");
  write_interval(out, p.wilson, nullptr);
  out.key("clopper_pearson");
  write_interval(out, p.clopper_pearson, nullptr);
  out.end_object();
}

}  // namespace

void write_study_json(JsonWriter& out, const StudySpec& spec, const StudyAnswers& answers, const std::function<void(JsonWriter&)>& more) {
  out.begin_object();
  out.key("method").value(to_string(spec.method)).key("samples").value(static_cast<long>(spec.samples));
  out.key("seed").value(static_cast<long>(spec.seed)).key("sensitivity").value(spec.sensitivity);
  out.key("confidence").value(spec.confidence).key("cases").value(static_cast<long>(answers.cases));
  out.key("statistical_samples").value(static_cast<long>(answers.samples)).key("failed").value(static_cast<long>(answers.failed));
  out.key("parameters").begin_array();
  for (const UncertainParameter& p : spec.parameters) {
    out.begin_object().key("name").value(p.name).key("distribution").value(p.written);
    out.key("mean").value(p.marginal.mean()).key("standard_deviation").value(p.marginal.standard_deviation());
    out.key("unit").value(p.marginal.dimension.si_unit()).end_object();
  }
  out.end_array();
  out.key("outputs").begin_object();
  for (const OutputAnswer& a : answers.outputs) {
    const StudyColumn& c = a.column;
    out.key(c.label).begin_object();
    out.key("unit").value(c.dimension.si_unit()).key("n").value(static_cast<long>(a.moments.n)).key("failed").value(static_cast<long>(a.failed));
    if (a.moments.n > 0) {
      out.key("mean").value(to_si(a.moments.mean, c)).key("standard_deviation").value(a.moments.standard_deviation * c.scale);
      out.key("mean_interval");
      write_interval(out, a.moments.mean_interval, &c);
      out.key("min").value(to_si(a.moments.min, c)).key("max").value(to_si(a.moments.max, c));
    }
    out.key("quantiles").begin_array();
    for (const QuantileEstimate& q : a.quantiles) {
      out.begin_object().key("level").value(q.level).key("value").value(to_si(q.value, c)).key("interval");
      write_interval(out, q.interval, &c);
      out.end_object();
    }
    out.end_array();
    out.key("histogram").begin_object().key("low").value(to_si(a.histogram.low, c)).key("width").value(a.histogram.width * c.scale);
    out.key("counts").begin_array();
    for (std::size_t n : a.histogram.counts) out.value(static_cast<long>(n));
    out.end_array().end_object();
    if (a.limits) {
      out.key("limits").begin_object();
      out.key("lower");
      a.limits->lower ? out.value(*a.limits->lower) : out.null();
      out.key("upper");
      a.limits->upper ? out.value(*a.limits->upper) : out.null();
      out.end_object();
    }
    if (a.capability) {
      const Capability& k = *a.capability;
      out.key("cp");
      k.cp ? out.value(*k.cp) : out.null();
      out.key("cpk");
      k.cpk ? out.value(*k.cpk) : out.null();
      out.key("ppm_normal").value(k.ppm_normal).key("ppm").value(1e6 * k.out_of_spec.estimate);
      out.key("out_of_spec");
      write_proportion(out, k.out_of_spec, [&k](JsonWriter& j) {
        j.key("below").value(static_cast<long>(k.below)).key("above").value(static_cast<long>(k.above));
      });
      out.key("ppm_or_failed").value(1e6 * k.out_of_spec_or_failed.estimate);
      out.key("out_of_spec_or_failed");
      write_proportion(out, k.out_of_spec_or_failed, [&k](JsonWriter& j) { j.key("failed").value(static_cast<long>(k.failed)); });
    }
    if (a.sobol) {
      out.key("sobol").begin_object().key("samples").value(static_cast<long>(a.sobol->samples));
      out.key("variance").value(a.sobol->variance * c.scale * c.scale).key("indices").begin_object();
      for (std::size_t j = 0; j < a.sobol->indices.size(); ++j) {
        const SobolIndex& s = a.sobol->indices[j];
        out.key(spec.parameters[j].name).begin_object().key("first").value(s.first).key("first_interval");
        write_interval(out, s.first_interval, nullptr);
        out.key("total").value(s.total).key("total_interval");
        write_interval(out, s.total_interval, nullptr);
        out.end_object();
      }
      out.end_object().end_object();
    }
    out.end_object();
  }
  out.end_object();
  out.key("events").begin_object();
  for (const EventAnswer& e : answers.events) {
    out.key(e.event->name);
    write_proportion(out, e.probability, [&e](JsonWriter& j) { j.key("undecided").value(static_cast<long>(e.undecided)); });
  }
  out.end_object();
  if (more) more(out);
  out.end_object();
}

}  // namespace mechgraph
