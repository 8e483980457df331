// The Abaqus UMAT entry of the ACST model (calibration/umat.h): conversions between the UMAT's
// conventions and the model's, the state in STATEV, the parameters from PROPS or a file, and the
// step cut through PNEWDT.
#include "calibration/umat.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>

#include "calibration/acst_model.h"

namespace {

using calibration::Parameters;
using calibration::State;
using calibration::Tensor;

thread_local std::string last_message;

// Abaqus order 11, 22, 33, 12, 13, 23.
constexpr int kRow[6] = {0, 1, 2, 0, 0, 1};
constexpr int kCol[6] = {0, 1, 2, 1, 2, 2};

// A symmetric tensor from the first `n` Abaqus components (the others 0); `shear_scale` 0.5 turns
// engineering shear strains into tensor ones.
Tensor<double> from_abaqus(const double* v, int n, double sign, double shear_scale) {
  Tensor<double> t = Tensor<double>::Zero();
  for (int k = 0; k < n; ++k) {
    const double x = sign * v[k] * (k < 3 ? 1.0 : shear_scale);
    t(kRow[k], kCol[k]) = x;
    t(kCol[k], kRow[k]) = x;
  }
  return t;
}

void to_abaqus(const Tensor<double>& t, double* v, int n, double sign) {
  for (int k = 0; k < n; ++k) v[k] = sign * t(kRow[k], kCol[k]);
}

// The parameters in the order of umat.h (that of kParameterFields): the first `count` from
// PROPS, the rest (added after the first version, e.g. n_b_loose) at their value_if_absent.
Parameters<double> parameters_from(const double* p, int count) {
  Parameters<double> par;
  for (std::size_t k = 0; k < calibration::kParameterFields<double>.size(); ++k) {
    const auto& field = calibration::kParameterFields<double>[k];
    par.*field.member = static_cast<int>(k) < count ? p[k] : field.value_if_absent;
  }
  return par;
}

// The parameter file named by SFFCAL_ACST_PARAMETERS, read once per path (thread-safe).
Parameters<double> parameters_from_file() {
  static std::mutex mutex;
  static std::string path_read, error;
  static Parameters<double> cached;
  const char* path = std::getenv("SFFCAL_ACST_PARAMETERS");
  if (!path || !*path)
    throw std::runtime_error(
        "NPROPS < 22 and no parameter file: set SFFCAL_ACST_PARAMETERS to the ACST parameter "
        "file (JSON), or give the 15 parameters in PROPS(8..22)");
  const std::lock_guard<std::mutex> lock(mutex);
  if (path_read != path) {
    path_read = path;
    error.clear();
    try {
      cached = calibration::read_parameters_json(path);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  if (!error.empty()) throw std::runtime_error(error);
  return cached;
}

// Hypoelastic stiffness of Eq. (1) at the state, Abaqus layout (engineering shear), for DDSDDE
// when an update fails (it must stay finite).
void elastic_ddsdde(const Parameters<double>& par, const State<double>& s, double* ddsdde, int n) {
  for (int i = 0; i < n * n; ++i) ddsdde[i] = 0.0;
  const double p = s.stress.trace() / 3.0;
  if (!(p > 0.0) || !(s.void_ratio > 0.0) || !(s.void_ratio < 2.97)) return;
  double G = 0.0, K = 0.0;
  calibration::detail::elastic_moduli(par, p, s.void_ratio, G, K);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) ddsdde[i + n * j] = K - 2.0 * G / 3.0 + (i == j ? 2.0 * G : 0.0);
  for (int k = 3; k < n; ++k) ddsdde[k + n * k] = G;
}

void report(const std::string& message, const int* noel, const int* npt, double* pnewdt) {
  last_message = message;
  std::fprintf(stderr, "sffcal_umat: element %d point %d: %s; asking for a smaller increment\n",
               noel ? *noel : -1, npt ? *npt : -1, message.c_str());
  if (pnewdt) *pnewdt = std::min(*pnewdt, 0.5);
}

}  // namespace

extern "C" {

const char* sffcal_umat_last_message(void) { return last_message.c_str(); }

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
  last_message.clear();
  const int n = *ntens;
  try {
    if (*ndi != 3 || !((*nshr == 3 && n == 6) || (*nshr == 1 && n == 4)))
      throw std::runtime_error("NDI = " + std::to_string(*ndi) + ", NSHR = " +
                               std::to_string(*nshr) + ": only 3D (NTENS = 6) and plane strain or "
                               "axisymmetric elements (NTENS = 4) are supported");
    if (*nstatv < SFFCAL_UMAT_NSTATV)
      throw std::runtime_error("NSTATV = " + std::to_string(*nstatv) + ", at least " +
                               std::to_string(static_cast<int>(SFFCAL_UMAT_NSTATV)) + " needed");
    if (*nprops < SFFCAL_UMAT_NPROPS_STATE)
      throw std::runtime_error("NPROPS = " + std::to_string(*nprops) +
                               ": PROPS(1..7) must give e_0 and F_0");
    const Parameters<double> par =
        *nprops >= SFFCAL_UMAT_NPROPS_ALL
            ? parameters_from(props + SFFCAL_UMAT_PROP_PARAMETERS,
                              *nprops - SFFCAL_UMAT_PROP_PARAMETERS)
            : parameters_from_file();
    calibration::validate_parameters(par);

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
    calibration::UpdateReport update_report;
    const calibration::UpdateStatus status = calibration::update_with_tangent(
        par, start, increment, end, D, calibration::IntegrationOptions(), &update_report);
    if (status == calibration::UpdateStatus::kFailed) {
      elastic_ddsdde(par, start, ddsdde, n);
      report("update failed: " + update_report.message, noel, npt, pnewdt);
      return;
    }
    to_abaqus(end.stress, stress, n, -1.0);
    // DDSDDE(I, J) = d sigma_I / d eps_J with engineering shear: the symmetrised D(ij, kl) for
    // a shear J = kl (d sigma_ij = D(ij,kl) d gamma_kl), D(ij, kk) for a normal one; the two sign
    // flips cancel.
    for (int I = 0; I < n; ++I)
      for (int J = 0; J < n; ++J)
        ddsdde[I + n * J] = D(3 * kRow[I] + kCol[I], 3 * kRow[J] + kCol[J]);
    statev[SFFCAL_UMAT_STATE_INITIALISED] = 1.0;
    statev[SFFCAL_UMAT_STATE_VOID_RATIO] = end.void_ratio;
    to_abaqus(end.alpha, statev + SFFCAL_UMAT_STATE_ALPHA, 6, 1.0);
    to_abaqus(end.alpha_in, statev + SFFCAL_UMAT_STATE_ALPHA_IN, 6, 1.0);
    to_abaqus(end.fabric, statev + SFFCAL_UMAT_STATE_FABRIC, 6, 1.0);
    statev[SFFCAL_UMAT_STATE_STATUS] = status == calibration::UpdateStatus::kOk ? 0.0 : 1.0;
    statev[SFFCAL_UMAT_STATE_SUBSTEPS] = static_cast<double>(update_report.substeps);
    if (status == calibration::UpdateStatus::kUnreliable)
      report("unreliable update: " + update_report.message, noel, npt, pnewdt);
  } catch (const std::exception& e) {
    for (int i = 0; i < n * n; ++i) ddsdde[i] = 0.0;
    report(e.what(), noel, npt, pnewdt);
  }
}

}  // extern "C"
