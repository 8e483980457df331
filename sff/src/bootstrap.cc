#include "sff/bootstrap.h"

#include <algorithm>
#include <array>
#include <exception>
#include <random>
#include <vector>

#include "sff/analysis.h"
#include "sff/tensors.h"

namespace sff {
namespace {

__extension__ using Uint128 = unsigned __int128;  // GCC/Clang; __extension__ keeps -Wpedantic quiet

std::array<double, 4> coefficients(ContactSpan contacts, const ForceScale& scale, double friction) {
  const DirectionalTensors t = directional_tensors(contacts, scale, friction);
  return {triaxial(t.fabric), triaxial(t.normal), triaxial(t.tangential), triaxial(t.mobilisation)};
}

// Linear interpolation between order statistics.
double percentile(std::vector<double> values, double fraction) {
  std::sort(values.begin(), values.end());
  const double position = fraction * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(position);
  const std::size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (position - static_cast<double>(below)) * (values[above] - values[below]);
}

}  // namespace

BootstrapIntervals bootstrap_coefficients(ContactSpan contacts, const ForceScale& scale,
                                          double friction, int resamples, std::uint64_t seed) {
  if (resamples < 2) throw StatisticsError("bootstrap_coefficients: at least 2 resamples");
  std::vector<std::size_t> body_contacts;
  for (std::size_t k = 0; k < contacts.size(); ++k)
    if (!is_wall_contact(contacts[k])) body_contacts.push_back(k);
  if (body_contacts.empty()) throw StatisticsError("bootstrap_coefficients: no body-body contacts");
  const ContactSpan plain(contacts.begin(), contacts.size());

  std::vector<std::array<double, 4>> samples(static_cast<std::size_t>(resamples));
  std::exception_ptr failure;
#pragma omp parallel
  {
    std::vector<double> multiplicity(contacts.size());
#pragma omp for schedule(static)
    for (int r = 0; r < resamples; ++r) {
      try {
        std::seed_seq seeds{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                            static_cast<std::uint32_t>(r)};
        std::mt19937_64 rng(seeds);
        std::fill(multiplicity.begin(), multiplicity.end(), 0.0);
        const auto n = static_cast<Uint128>(body_contacts.size());
        for (std::size_t k = 0; k < body_contacts.size(); ++k) {
          // Lemire's multiply-shift: a uniform index in [0, n) from one 64-bit draw.
          const auto pick = static_cast<std::size_t>((static_cast<Uint128>(rng()) * n) >> 64);
          multiplicity[body_contacts[pick]] += 1.0;
        }
        samples[static_cast<std::size_t>(r)] = coefficients(plain.weighted(multiplicity), scale, friction);
      } catch (...) {
#pragma omp critical(sff_bootstrap_failure)
        if (!failure) failure = std::current_exception();
      }
    }
  }
  if (failure) std::rethrow_exception(failure);

  const std::array<double, 4> estimate = coefficients(plain, scale, friction);
  std::array<Interval, 4> intervals;
  for (std::size_t q = 0; q < 4; ++q) {
    std::vector<double> values(samples.size());
    for (std::size_t r = 0; r < samples.size(); ++r) values[r] = samples[r][q];
    intervals[q] = {estimate[q], percentile(values, 0.025), percentile(values, 0.975)};
  }
  BootstrapIntervals result;
  result.a_c = intervals[0];
  result.a_n = intervals[1];
  result.a_t = intervals[2];
  result.m = intervals[3];
  result.resamples = resamples;
  result.seed = seed;
  return result;
}

}  // namespace sff
