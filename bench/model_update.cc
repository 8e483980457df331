// Cost of one ACST stress update with and without its consistent tangent (issue 14), for the two
// integrations in one run: the implicit one (the FE default: one second-order step per
// increment; and with error control at 1e-3) against the explicit reference at its former
// defaults (tolerance 1e-6, the library's, and 1e-9, fe-check's; tangent by Jets through the
// substeps).
//
// Cases (Toyoura-like parameters of docs/model.md, p0 = 100 kPa, F0 = 0.3 n_c):
//   plastic    a medium-dense specimen (e0 = 0.80) at 1 % drained axial strain, on the yield
//              surface, loaded by a general 3D strain increment of 5e-4 or 3e-3 (axial part);
//   crossing   the isotropic specimen, first loading by the same 5e-4 increment: the elastic
//              part in the cone, the crossing, then plastic.
//
// BM_UpdateWithTangentElasticExponent: the implicit FE default at n_G = 0.5 (DM04's exponent,
// square roots), 0.3 and 0.1 (pow, log1p and expm1 in the elastic path), the same 5e-4 cases.
// BM_UpdateWithTangentFabricRate: the same at n_F = 0 (LD12's constant fabric rate) and 13 (the
// mean-of-three fit's), whose rate's psi terms enter the local Jacobian and the tangent.
//
//   model_update --benchmark_repetitions=10 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <Eigen/Core>

#include <string>

#include "model/acst_model.h"
#include "model/material_point.h"

namespace {

using model::acst::IntegrationOptions;
using model::acst::State;
using model::acst::Tensor;

// The Toyoura-like parameters of docs/model.md, from the example parameter file.
const model::acst::Parameters<double>& toyoura() {
  static const model::acst::Parameters<double> p =
      model::acst::read_parameters_json(SFFCAL_SOURCE_DIR "/examples/acst_toyoura.json");
  return p;
}

State<double> isotropic() {
  return model::acst::isotropic_state(100e3, 0.80, model::acst::triaxial_deviator(0.3));
}

State<double> plastic() {
  static const State<double> s =
      model::acst::drained_triaxial(toyoura(), isotropic(), 0.01, 50).state;
  return s;
}

Tensor<double> increment(double axial) {
  Tensor<double> d;
  d << -0.3, 0.1, -0.05,  //
      0.1, -0.25, 0.08,   //
      -0.05, 0.08, 1.0;
  return axial * d;
}

IntegrationOptions integration(int which) {
  switch (which) {
    case 0:
      return IntegrationOptions();  // implicit, FE default
    case 1:
      return IntegrationOptions::implicit_controlled(1e-3);
    case 2:
      return IntegrationOptions::explicit_reference(1e-6);
    default:
      return IntegrationOptions::explicit_reference(1e-9);
  }
}

const char* integration_name(int which) {
  static const char* const names[] = {"implicit", "implicit_tol1e-3", "explicit_tol1e-6",
                                      "explicit_tol1e-9"};
  return names[which];
}

// state: 0 plastic, 1 isotropic (crossing); size in 1e-4 of axial strain.
void run(benchmark::State& bench, bool with_tangent) {
  const int which = static_cast<int>(bench.range(0));
  const State<double> start = bench.range(1) == 0 ? plastic() : isotropic();
  const Tensor<double> deps = increment(1e-4 * static_cast<double>(bench.range(2)));
  const IntegrationOptions options = integration(which);
  const model::acst::Parameters<double>& par = toyoura();
  State<double> end;
  Eigen::Matrix<double, 9, 9> tangent;
  long substeps = 0;
  model::acst::update_state(par, start, deps, end, options, &substeps);
  for (auto _ : bench) {
    const model::acst::UpdateStatus status =
        with_tangent ? model::acst::update_with_tangent(par, start, deps, end, tangent, options)
                     : model::acst::update_state(par, start, deps, end, options);
    benchmark::DoNotOptimize(status);
    benchmark::DoNotOptimize(end.stress.data());
    benchmark::DoNotOptimize(tangent.data());
  }
  bench.SetLabel(std::string(integration_name(which)) +
                 (bench.range(1) == 0 ? " plastic" : " crossing") + " substeps=" +
                 std::to_string(substeps));
}

void BM_Update(benchmark::State& bench) { run(bench, false); }
void BM_UpdateWithTangent(benchmark::State& bench) { run(bench, true); }

// {integration, state, axial increment in 1e-4}
void cases(benchmark::internal::Benchmark* b) {
  for (int which = 0; which < 4; ++which) {
    b->Args({which, 0, 5});
    b->Args({which, 0, 30});
    b->Args({which, 1, 5});
  }
  b->Unit(benchmark::kMicrosecond);
}

// The implicit FE default with the tangent, increment 5e-4, from the state bench.range(1) names
// (0: plastic, 1: crossing), with `par`; labelled `what` and the state.
void update_with_tangent_of(benchmark::State& bench, const model::acst::Parameters<double>& par,
                            const std::string& what) {
  const State<double> start = bench.range(1) == 0 ? plastic() : isotropic();
  const Tensor<double> deps = increment(5e-4);
  State<double> end;
  Eigen::Matrix<double, 9, 9> tangent;
  for (auto _ : bench) {
    const model::acst::UpdateStatus status =
        model::acst::update_with_tangent(par, start, deps, end, tangent, IntegrationOptions());
    benchmark::DoNotOptimize(status);
    benchmark::DoNotOptimize(end.stress.data());
    benchmark::DoNotOptimize(tangent.data());
  }
  bench.SetLabel(what + (bench.range(1) == 0 ? " plastic" : " crossing"));
}

// {n_G in 1e-2, state}.
void BM_UpdateWithTangentElasticExponent(benchmark::State& bench) {
  model::acst::Parameters<double> par = toyoura();
  par.n_G = 1e-2 * static_cast<double>(bench.range(0));
  update_with_tangent_of(bench, par, "n_G " + std::to_string(par.n_G).substr(0, 4));
}

// {n_F, state}.
void BM_UpdateWithTangentFabricRate(benchmark::State& bench) {
  model::acst::Parameters<double> par = toyoura();
  par.n_F = static_cast<double>(bench.range(0));
  update_with_tangent_of(bench, par, "n_F " + std::to_string(bench.range(0)));
}

BENCHMARK(BM_Update)->Apply(cases);
BENCHMARK(BM_UpdateWithTangent)->Apply(cases);
BENCHMARK(BM_UpdateWithTangentElasticExponent)
    ->ArgsProduct({{50, 30, 10}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_UpdateWithTangentFabricRate)
    ->ArgsProduct({{0, 13}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
