#include <mechgraph/uncertainty/sample_design.hpp>

#include <mechgraph/display_units.hpp>

#include <mechgraph/errors.hpp>
#include <mechgraph/large_arrays.hpp>
#include <mechgraph/chunked_work.hpp>

#include <boost/random/sobol.hpp>

#include <algorithm>
#include <charconv>
#include <memory>
#include <cmath>
#include <numeric>

namespace mechgraph {
namespace {

std::uint64_t splitmix(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// (x >> 11 + 1/2) 2^-53: strictly inside (0, 1), so every quantile is finite.
double open_unit(std::uint64_t x) { return (static_cast<double>(x >> 11) + 0.5) * 0x1.0p-53; }

// The streams of counter_hash: which use of random numbers a value belongs to.
constexpr std::uint64_t stream_monte_carlo = 1, stream_lhs_jitter = 2, stream_lhs_permutation = 3, stream_sobol_shift = 4;

}  // namespace

std::uint64_t counter_hash(std::uint64_t seed, std::uint64_t stream, std::uint64_t i, std::uint64_t j) {
  return splitmix(splitmix(splitmix(splitmix(seed) ^ stream) ^ i) ^ j);
}

double counter_uniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t i, std::uint64_t j) {
  return open_unit(counter_hash(seed, stream, i, j));
}

CounterRow::CounterRow(std::uint64_t seed, std::uint64_t stream, std::uint64_t i)
    : prefix_(splitmix(splitmix(splitmix(seed) ^ stream) ^ i)) {}

double CounterRow::operator()(std::uint64_t j) const { return open_unit(splitmix(prefix_ ^ j)); }

UnitDesign::UnitDesign(SamplingMethod method, std::size_t n, std::size_t dims, std::uint64_t seed)
    : method_(method), n_(n), dims_(dims), seed_(seed) {
  if (method == SamplingMethod::latin_hypercube) {
    // One permutation of the n strata per dimension (Fisher-Yates, each swap drawn from the counter).
    strata_.resize(n * dims);
    for (std::size_t j = 0; j < dims; ++j) {
      std::uint32_t* pi = strata_.data() + j * n;
      std::iota(pi, pi + n, std::uint32_t{0});
      for (std::size_t i = n; i-- > 1;) {
        const auto k = static_cast<std::size_t>(counter_uniform(seed, stream_lhs_permutation, j, i) * static_cast<double>(i + 1));
        std::swap(pi[i], pi[std::min(k, i)]);
      }
    }
  } else if (method == SamplingMethod::sobol) {
    if (dims > boost::random::detail::qrng_tables::sobol::max_dimension)  // not reached: at most 2 x 1000 dimensions
      throw SceneError("Sobol' sequence: " + std::to_string(dims) + " dimensions are more than Boost's " +
                       std::to_string(boost::random::detail::qrng_tables::sobol::max_dimension));
    for (std::size_t j = 0; j < dims; ++j) shift_.push_back(counter_hash(seed, stream_sobol_shift, 0, j));
  }
}

void UnitDesign::point(std::size_t i, double* out) const {
  switch (method_) {
    case SamplingMethod::monte_carlo:
      for (std::size_t j = 0; j < dims_; ++j) out[j] = counter_uniform(seed_, stream_monte_carlo, i, j);
      return;
    case SamplingMethod::latin_hypercube:
      for (std::size_t j = 0; j < dims_; ++j)
        out[j] = (static_cast<double>(strata_[j * n_ + i]) + counter_uniform(seed_, stream_lhs_jitter, i, j)) / static_cast<double>(n_);
      return;
    case SamplingMethod::sobol: {
      // Point i of the sequence, its 64-bit coordinates XORed with the digital shift. Point 0 is
      // the origin; Boost's generator starts at point 1, and seed(k) makes point k + 1 the next.
      if (i == 0) {
        for (std::size_t j = 0; j < dims_; ++j) out[j] = open_unit(shift_[j]);
        return;
      }
      thread_local std::unique_ptr<boost::random::sobol> engine;
      thread_local std::size_t engine_dims = 0, engine_next = 0;  // engine_next: the point the next read gives
      if (!engine || engine_dims != dims_) {
        engine = std::make_unique<boost::random::sobol>(dims_);
        engine_dims = dims_;
        engine_next = 1;
      }
      if (engine_next != i) engine->seed(static_cast<boost::random::sobol::result_type>(i - 1));
      for (std::size_t j = 0; j < dims_; ++j) out[j] = open_unit(static_cast<std::uint64_t>((*engine)()) ^ shift_[j]);
      engine_next = i + 1;
      return;
    }
  }
}

namespace {

// The lower Cholesky factor L (L L^T = R) of the correlation matrix of the Gaussian copula;
// throws naming the first correlation when R is not positive definite.
std::vector<double> cholesky(const StudySpec& spec) {
  const std::size_t d = spec.parameters.size();
  std::vector<double> r(d * d, 0.0), l(d * d, 0.0);
  for (std::size_t j = 0; j < d; ++j) r[j * d + j] = 1.0;
  for (const ParameterCorrelation& c : spec.correlations) r[c.first * d + c.second] = r[c.second * d + c.first] = c.rho;
  for (std::size_t j = 0; j < d; ++j) {
    for (std::size_t k = 0; k <= j; ++k) {
      double s = r[j * d + k];
      for (std::size_t m = 0; m < k; ++m) s -= l[j * d + m] * l[k * d + m];
      if (j == k) {
        if (!(s > 1e-12))
          throw SceneError(spec.correlations.front().where.str() +
                           "the correlations do not make a valid correlation matrix (not positive definite): no set of "
                           "parameters can be correlated so");
        l[j * d + j] = std::sqrt(s);
      } else {
        l[j * d + k] = s / l[k * d + k];
      }
    }
  }
  return l;
}

}  // namespace

std::string design_size_excess(const StudySpec& spec, std::size_t max_values, const std::string& holder) {
  const std::size_t d = spec.parameters.size(), n = spec.samples;
  const std::size_t per_sample = spec.sensitivity ? d + 2 : 1;
  if (spec.evaluations() * std::max<std::size_t>(d, 1) <= max_values) return {};
  return "samples: " + std::to_string(n) + " make " + std::to_string(spec.evaluations()) + " cases of " + std::to_string(d) +
         " values each, more than the " + std::to_string(max_values) + " values " + holder + "; at most " +
         std::to_string(max_values / (per_sample * std::max<std::size_t>(d, 1))) + " samples here" +
         (spec.sensitivity ? " with sensitivity (" + std::to_string(per_sample) + " cases a sample)" : std::string());
}

void check_design_size(const StudySpec& spec) {
  if (const std::string excess = design_size_excess(spec, max_design_values, "one study's design holds in memory"); !excess.empty())
    throw SceneError("uncertainty: " + excess + ", or split the parameters into studies of fewer");
}

CaseTable make_study_cases(const StudySpec& spec, unsigned threads) {
  const std::size_t d = spec.parameters.size(), n = spec.samples;
  const std::size_t per_sample = spec.sensitivity ? d + 2 : 1;
  check_design_size(spec);
  CaseTable table;
  for (const UncertainParameter& p : spec.parameters) table.variables.push_back({p.name, p.unit});
  table.origin = "uncertainty: " + to_string(spec.method) + ", " + std::to_string(n) + " samples, seed " + std::to_string(spec.seed) +
                 (spec.sensitivity ? ", Saltelli design (" + std::to_string(per_sample) + " cases a sample)" : "");
  const UnitDesign design(spec.method, n, spec.sensitivity ? 2 * d : d, spec.seed);
  const std::vector<double> l = spec.correlations.empty() ? std::vector<double>{} : cholesky(spec);
  // Numbers only, compactly (CaseTable::Numbers): one allocation for the whole design.
  table.numbers.count = n * per_sample;
  for (const UncertainParameter& p : spec.parameters) table.numbers.dimensions.push_back(p.marginal.dimension);
  reserve_large(table.numbers.si, table.numbers.count * d);
  table.numbers.si.resize(table.numbers.count * d);
  // Sample i fills rows i * per_sample ...: samples are independent (each point of the design is
  // fixed by its index), so chunks of them run on `threads` workers with the same table.
  constexpr std::size_t samples_per_chunk = 4096;
  const std::size_t chunks = (n + samples_per_chunk - 1) / samples_per_chunk;
  struct Worker {
    std::vector<double> u, z, a, b;
  };
  const auto make_worker = [&] { return Worker{std::vector<double>(design.dims()), std::vector<double>(d), std::vector<double>(d),
                                               std::vector<double>(d)}; };
  // Each parameter's unit, parsed once: its values are put on the numbers of that unit (below).
  std::vector<std::optional<UnitScale>> units;
  for (const UncertainParameter& p : spec.parameters) units.push_back(p.unit.empty() ? std::nullopt : parse_unit_cached(p.unit));
  run_chunks(chunks, threads, make_worker, [&](Worker& w, std::size_t chunk) {
    const auto to_values = [&](const double* unit, std::vector<double>& x) {
      if (l.empty()) {
        for (std::size_t j = 0; j < d; ++j) x[j] = spec.parameters[j].marginal.quantile(unit[j]);
        return;
      }
      // Gaussian copula: normal scores, correlated by L, back to (0, 1), through each quantile.
      for (std::size_t j = 0; j < d; ++j) w.z[j] = standard_normal_quantile(unit[j]);
      for (std::size_t j = 0; j < d; ++j) {
        double s = 0.0;
        for (std::size_t k = 0; k <= j; ++k) s += l[j * d + k] * w.z[k];
        const double v = std::clamp(standard_normal_cdf(s), 0x1.0p-60, 1.0 - 0x1.0p-53);
        x[j] = spec.parameters[j].marginal.quantile(v);
      }
    };
    // Each value on the numbers of the unit its parameter was written in, so that its rows show
    // it there exactly (their text made when asked). Value by value: the rows A_B^(j) of
    // Saltelli's design are made of A's and B's values as put there.
    const auto put = [&](std::vector<double>& x) {
      for (std::size_t j = 0; j < d; ++j) x[j] = expressible_in(x[j], units[j]);
    };
    const auto row = [&](std::size_t case_index) { return table.numbers.si.data() + case_index * d; };
    for (std::size_t i = chunk * samples_per_chunk; i < std::min(n, (chunk + 1) * samples_per_chunk); ++i) {
      const std::size_t first = i * per_sample;
      design.point(i, w.u.data());
      to_values(w.u.data(), w.a);
      put(w.a);
      std::copy(w.a.begin(), w.a.end(), row(first));
      if (!spec.sensitivity) continue;
      to_values(w.u.data() + d, w.b);
      put(w.b);
      std::copy(w.b.begin(), w.b.end(), row(first + 1));
      for (std::size_t j = 0; j < d; ++j) {
        double* ab = row(first + 2 + j);
        std::copy(w.a.begin(), w.a.end(), ab);
        ab[j] = w.b[j];
      }
    }
  });
  return table;
}

}  // namespace mechgraph
