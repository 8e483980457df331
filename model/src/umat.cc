// The Abaqus UMAT entry of the ACST model (model/umat.h): conversions between the UMAT's
// conventions and the model's, the state in STATEV, the parameters from PROPS or a file, and the
// step cut through PNEWDT.
#include "model/umat.h"

#include <cmath>
#include <string>

#include "model/acst_model.h"
#include "umat_common.h"

namespace {

using model::acst::Parameters;
using model::acst::State;
using model::acst::Tensor;

using model::umat_detail::from_abaqus;
using model::umat_detail::report;
using model::umat_detail::to_abaqus;

// The parameters in the order of umat.h (that of kParameterFields): the first `count` from
// PROPS, the rest (added after the first version, e.g. n_b_loose) at their value_if_absent.
Parameters<double> parameters_from(const double* p, int count) {
  Parameters<double> par;
  for (std::size_t k = 0; k < model::acst::kParameterFields<double>.size(); ++k) {
    const auto& field = model::acst::kParameterFields<double>[k];
    par.*field.member = static_cast<int>(k) < count ? p[k] : field.value_if_absent;
  }
  return par;
}

// The parameter file named by SFFCAL_ACST_PARAMETERS, read once per path.
Parameters<double> parameters_from_file() {
  return model::umat_detail::read_file_once<Parameters<double>>(
      "SFFCAL_ACST_PARAMETERS",
      "NPROPS < 22 and no parameter file: set SFFCAL_ACST_PARAMETERS to the ACST parameter file "
      "(JSON), or give the 15 parameters in PROPS(8..22)",
      [](const std::string& path) { return model::acst::read_parameters_json(path); });
}

// Hypoelastic stiffness of Eq. (1) at the state, Abaqus layout (engineering shear), for DDSDDE
// when an update fails (it must stay finite).
void elastic_ddsdde(const Parameters<double>& par, const State<double>& s, double* ddsdde, int n) {
  for (int i = 0; i < n * n; ++i) ddsdde[i] = 0.0;
  const double p = s.stress.trace() / 3.0;
  if (!(p > 0.0) || !(s.void_ratio > 0.0) || !(s.void_ratio < 2.97)) return;
  double G = 0.0, K = 0.0;
  model::acst::detail::elastic_moduli(par, p, s.void_ratio, G, K);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) ddsdde[i + n * j] = K - 2.0 * G / 3.0 + (i == j ? 2.0 * G : 0.0);
  for (int k = 3; k < n; ++k) ddsdde[k + n * k] = G;
}

}  // namespace

extern "C" {

void sffcal_umat(double* stress, double* statev, double* ddsdde, double* /*sse*/,
                 double* /*spd*/, double* /*scd*/, double* /*rpl*/, double* /*ddsddt*/,
                 double* /*drplde*/, double* /*drpldt*/, const double* /*stran*/,
                 const double* dstran, const double* /*time*/, const double* /*dtime*/,
                 const double* /*temp*/, const double* /*dtemp*/, const double* /*predef*/,
                 const double* /*dpred*/, const char* /*cmname*/, const int* ndi,
                 const int* nshr, const int* ntens, const int* nstatv, const double* props,
                 const int* nprops, const double* /*coords*/, const double* /*drot*/,
                 double* pnewdt, const double* /*celent*/, const double* /*dfgrd0*/,
                 const double* /*dfgrd1*/, const int* noel, const int* npt, const int* /*layer*/,
                 const int* /*kspt*/, const int* /*kstep*/, const int* /*kinc*/,
                 size_t /*cmname_length*/) {
  model::umat_detail::last_message().clear();
  const int n = *ntens;
  try {
    model::umat_detail::check_layout(*ndi, *nshr, n, *nstatv, SFFCAL_UMAT_NSTATV);
    if (*nprops < SFFCAL_UMAT_NPROPS_STATE)
      throw std::runtime_error("NPROPS = " + std::to_string(*nprops) +
                               ": PROPS(1..7) must give e_0 and F_0");
    const Parameters<double> par =
        *nprops >= SFFCAL_UMAT_NPROPS_ALL
            ? parameters_from(props + SFFCAL_UMAT_PROP_PARAMETERS,
                              *nprops - SFFCAL_UMAT_PROP_PARAMETERS)
            : parameters_from_file();
    model::acst::validate_parameters(par);

    State<double> start;
    start.stress = from_abaqus(stress, n, -1.0, 1.0);  // tension -> compression positive
    if (statev[SFFCAL_UMAT_STATE_INITIALISED] == 0.0) {
      const double p = start.stress.trace() / 3.0;
      start.void_ratio = props[SFFCAL_UMAT_PROP_VOID_RATIO];
      start.alpha = p > 0.0 ? Tensor<double>((start.stress - p * Tensor<double>::Identity()) / p)
                            : Tensor<double>(Tensor<double>::Zero());
      start.alpha_in = start.alpha;
      start.fabric = from_abaqus(props + SFFCAL_UMAT_PROP_FABRIC, 6, 1.0, 1.0);
    } else {
      start.void_ratio = statev[SFFCAL_UMAT_STATE_VOID_RATIO];
      start.alpha = from_abaqus(statev + SFFCAL_UMAT_STATE_ALPHA, 6, 1.0, 1.0);
      start.alpha_in = from_abaqus(statev + SFFCAL_UMAT_STATE_ALPHA_IN, 6, 1.0, 1.0);
      start.fabric = from_abaqus(statev + SFFCAL_UMAT_STATE_FABRIC, 6, 1.0, 1.0);
    }
    const Tensor<double> increment = from_abaqus(dstran, n, -1.0, 0.5);

    State<double> end;
    Eigen::Matrix<double, 9, 9> D;
    model::acst::UpdateReport update_report;
    const model::acst::UpdateStatus status = model::acst::update_with_tangent(
        par, start, increment, end, D, model::acst::IntegrationOptions(), &update_report);
    if (status == model::acst::UpdateStatus::kFailed) {
      elastic_ddsdde(par, start, ddsdde, n);
      report("update failed: " + update_report.message, noel, npt, pnewdt);
      return;
    }
    to_abaqus(end.stress, stress, n, -1.0);
    model::umat_detail::to_ddsdde(D, ddsdde, n);
    statev[SFFCAL_UMAT_STATE_INITIALISED] = 1.0;
    statev[SFFCAL_UMAT_STATE_VOID_RATIO] = end.void_ratio;
    to_abaqus(end.alpha, statev + SFFCAL_UMAT_STATE_ALPHA, 6, 1.0);
    to_abaqus(end.alpha_in, statev + SFFCAL_UMAT_STATE_ALPHA_IN, 6, 1.0);
    to_abaqus(end.fabric, statev + SFFCAL_UMAT_STATE_FABRIC, 6, 1.0);
    statev[SFFCAL_UMAT_STATE_STATUS] = status == model::acst::UpdateStatus::kOk ? 0.0 : 1.0;
    statev[SFFCAL_UMAT_STATE_SUBSTEPS] = static_cast<double>(update_report.substeps);
    if (status == model::acst::UpdateStatus::kUnreliable)
      report("unreliable update: " + update_report.message, noel, npt, pnewdt);
  } catch (const std::exception& e) {
    for (int i = 0; i < n * n; ++i) ddsdde[i] = 0.0;
    report(e.what(), noel, npt, pnewdt);
  }
}

}  // extern "C"
