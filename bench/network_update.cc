// Cost of one contact-network stress update with its exact tangent (fe_model::NetworkMaterial,
// docs/network-model.md), the figure that decides whether the second material is usable at FE
// speed; beside it the ACST update (AcstMaterial, the FE default) on the same increments.
//
// Cases: the contact-network parameters fitted to the four paper-size runs
// (bench/reference/network_paper_params.json) on the dense 100 kPa specimen's initial network
// (e 0.574, Z 6.69, isotropic), first sheared 3 % in drained compression by the FE element (past
// the peak); then a general 3D strain increment whose axial part is 5e-4 or 3e-3. ACST: the
// Toyoura-like example parameters on a medium-dense specimen after the same 3 %.
//
//   network_update --benchmark_repetitions=10 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "model/acst_model.h"
#include "fe_model/acst_material.h"
#include "fe_model/network_material.h"

namespace {

fe_model::SymmetricTensor2 increment(double axial) {  // tension positive, as fe_model takes it
  fe_model::SymmetricTensor2 d;
  d[0][0] = 0.3, d[1][1] = 0.25, d[2][2] = -1.0;
  d[0][1] = -0.1, d[1][2] = -0.08, d[0][2] = 0.05;
  return axial * d;
}

// The state of the single element's quadrature point after 3 % of drained compression.
fe_model::PointState sheared(const fe_model::Material& material) {
  fe_model::PointState state = material.initial_state(-100e3 * dealii::unit_symmetric_tensor<3>());
  fe_model::SymmetricTensor2 step;
  step[2][2] = -0.001;
  step[0][0] = step[1][1] = 0.0003;  // roughly the drained path: the state, not the path, matters
  for (int k = 0; k < 30; ++k) {
    fe_model::PointState end;
    material.update(state, step, end);
    state = end;
  }
  return state;
}

const fe_model::NetworkMaterial& network() {
  static const fe_model::NetworkMaterial material = [] {
    double modulus = 0.0;
    const auto par = model::network::read_parameters_json(
        SFFCAL_SOURCE_DIR "/bench/reference/network_paper_params.json", &modulus);
    fe_model::NetworkInitialState initial;
    initial.void_ratio = 0.574;
    initial.coordination = 6.69;
    return fe_model::NetworkMaterial(par, initial, modulus);
  }();
  return material;
}

const fe_model::AcstMaterial& acst() {
  static const fe_model::AcstMaterial material = [] {
    fe_model::AcstInitialState initial;
    initial.void_ratio = 0.80;
    return fe_model::AcstMaterial(
        model::acst::read_parameters_json(SFFCAL_SOURCE_DIR "/examples/acst_toyoura.json"),
        initial);
  }();
  return material;
}

void run(benchmark::State& bench, const fe_model::Material& material, double axial) {
  const fe_model::PointState start = sheared(material);
  const fe_model::SymmetricTensor2 d = increment(axial);
  fe_model::PointState end;
  for (auto _ : bench) {
    fe_model::MaterialUpdate update = material.update(start, d, end);
    benchmark::DoNotOptimize(update);
    benchmark::DoNotOptimize(end);
  }
}

void BM_NetworkUpdateWithTangent(benchmark::State& bench) {
  run(bench, network(), bench.range(0) == 0 ? 5e-4 : 3e-3);
}
void BM_AcstUpdateWithTangent(benchmark::State& bench) {
  run(bench, acst(), bench.range(0) == 0 ? 5e-4 : 3e-3);
}

}  // namespace

BENCHMARK(BM_NetworkUpdateWithTangent)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_AcstUpdateWithTangent)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
