// The Abaqus UMAT entry of the contact-network model (model/umat_network.h): the state in
// STATEV, E and the parameters from PROPS or a file, the update and its exact tangent from
// network_update.h, and the step cut through PNEWDT.
#include "model/umat_network.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "model/network_update.h"
#include "umat_common.h"

namespace {

namespace net = model::network;
using model::umat_detail::from_abaqus;
using model::umat_detail::report;
using model::umat_detail::to_abaqus;

struct Material {
  net::Parameters<double> parameters;
  double youngs_modulus = 0.0;  // [Pa]
};

Material material_from_props(const double* props, int nprops) {
  if (nprops == SFFCAL_UMAT_NETWORK_NPROPS_STATE) {
    return model::umat_detail::read_file_once<Material>(
        "SFFCAL_NETWORK_PARAMETERS",
        "NPROPS = 20 and no parameter file: set SFFCAL_NETWORK_PARAMETERS to the contact-network "
        "parameter file (JSON), or give E and the 18 parameters in PROPS(21..39)",
        [](const std::string& path) {
          Material read;
          read.parameters = net::read_parameters_json(path, &read.youngs_modulus);
          return read;
        });
  }
  if (nprops < SFFCAL_UMAT_NETWORK_NPROPS_ALL)
    throw std::runtime_error("NPROPS = " + std::to_string(nprops) +
                             ": give 20 (the initial network; E and the parameters from "
                             "SFFCAL_NETWORK_PARAMETERS), 39 (with E and the first 18 parameters), "
                             "40 (and c_t), 41 (and c_l), 42 (and n_kappa), 43 to 45 (and "
                             "d_psi, e_gamma, lambda_e), 46 (and w_psi), 47 (and r_i) or 48 "
                             "(and n_ra)");
  Material m;
  m.youngs_modulus = props[SFFCAL_UMAT_NETWORK_PROP_YOUNGS_MODULUS];
  if (!(m.youngs_modulus > 0.0) || !std::isfinite(m.youngs_modulus))
    throw std::runtime_error("PROPS(21), the grains' Young's modulus E = " +
                             std::to_string(m.youngs_modulus) + " Pa, must be > 0");
  // PROPS(22..39), the first version's 18 parameters, then c_t (PROPS(40)), c_l (PROPS(41)),
  // n_kappa (PROPS(42)), d_psi, e_gamma and lambda_e (PROPS(43..45)), w_psi (PROPS(46)), r_i
  // (PROPS(47)), n_ra (PROPS(48)) where given.
  double values[net::kNumParameters];
  for (int i = 0; i < net::kNumParameters; ++i)
    values[i] = SFFCAL_UMAT_NETWORK_PROP_PARAMETERS + i < nprops
                    ? props[SFFCAL_UMAT_NETWORK_PROP_PARAMETERS + i]
                    : net::value_if_absent(i);
  m.parameters = net::from_array(values);
  return m;
}

// A deviatoric tensor from PROPS(first + 1 .. first + 6); throws naming the PROPS otherwise.
Eigen::Matrix3d deviatoric_from_props(const double* props, int first, const char* name) {
  const Eigen::Matrix3d t = from_abaqus(props + first, 6, 1.0, 1.0);
  const std::string where = "PROPS(" + std::to_string(first + 1) + ".." +
                            std::to_string(first + 6) + "), the initial " + name;
  if (!t.allFinite()) throw std::runtime_error(where + ", is not finite");
  if (std::abs(t.trace()) > 1e-9 * std::max(1.0, t.norm()))
    throw std::runtime_error(where + ", has the trace " + std::to_string(t.trace()) +
                             ": it must be deviatoric");
  return t;
}

// The initial network from PROPS, Lambda from the mean stress of the initial STRESS.
net::State<double> initial_state(const double* props, const Eigen::Matrix3d& stress,
                                 double youngs_modulus) {
  net::State<double> s;
  s.void_ratio = props[SFFCAL_UMAT_NETWORK_PROP_VOID_RATIO];
  s.coordination = props[SFFCAL_UMAT_NETWORK_PROP_COORDINATION];
  if (!(s.void_ratio > 0.0) || !std::isfinite(s.void_ratio))
    throw std::runtime_error("PROPS(1), the initial void ratio " + std::to_string(s.void_ratio) +
                             ", must be > 0");
  if (!(s.coordination > 0.0) || !std::isfinite(s.coordination))
    throw std::runtime_error("PROPS(2), the initial coordination number " +
                             std::to_string(s.coordination) + ", must be > 0");
  s.fabric = deviatoric_from_props(props, SFFCAL_UMAT_NETWORK_PROP_FABRIC, "fabric anisotropy A");
  s.normal = deviatoric_from_props(props, SFFCAL_UMAT_NETWORK_PROP_NORMAL,
                                   "normal-force anisotropy F");
  s.tangential = deviatoric_from_props(props, SFFCAL_UMAT_NETWORK_PROP_TANGENTIAL,
                                       "tangential-force anisotropy F^t");
  s.inherent = s.fabric;  // the specimen's initial fabric is all its own (Eq. N2d)
  const double p = stress.trace() / 3.0;
  if (!(p > 0.0))
    throw std::runtime_error("the initial STRESS must be compressive (mean stress " +
                             std::to_string(-p) + " Pa, tension positive)");
  s.lambda = net::lambda_for_mean_stress(s, p, youngs_modulus);
  return s;
}

net::State<double> state_from_statev(const double* statev) {
  return {statev[SFFCAL_UMAT_NETWORK_STATE_VOID_RATIO],
          statev[SFFCAL_UMAT_NETWORK_STATE_COORDINATION],
          statev[SFFCAL_UMAT_NETWORK_STATE_LAMBDA],
          from_abaqus(statev + SFFCAL_UMAT_NETWORK_STATE_FABRIC, 6, 1.0, 1.0),
          from_abaqus(statev + SFFCAL_UMAT_NETWORK_STATE_NORMAL, 6, 1.0, 1.0),
          from_abaqus(statev + SFFCAL_UMAT_NETWORK_STATE_TANGENTIAL, 6, 1.0, 1.0),
          from_abaqus(statev + SFFCAL_UMAT_NETWORK_STATE_INHERENT, 6, 1.0, 1.0)};
}

void state_to_statev(const net::State<double>& s, double* statev) {
  statev[SFFCAL_UMAT_NETWORK_STATE_VOID_RATIO] = s.void_ratio;
  statev[SFFCAL_UMAT_NETWORK_STATE_COORDINATION] = s.coordination;
  statev[SFFCAL_UMAT_NETWORK_STATE_LAMBDA] = s.lambda;
  to_abaqus(s.fabric, statev + SFFCAL_UMAT_NETWORK_STATE_FABRIC, 6, 1.0);
  to_abaqus(s.normal, statev + SFFCAL_UMAT_NETWORK_STATE_NORMAL, 6, 1.0);
  to_abaqus(s.tangential, statev + SFFCAL_UMAT_NETWORK_STATE_TANGENTIAL, 6, 1.0);
  to_abaqus(s.inherent, statev + SFFCAL_UMAT_NETWORK_STATE_INHERENT, 6, 1.0);
}

}  // namespace

extern "C" {

int sffcal_umat_is_network_material(const char* cmname, size_t cmname_length) {
  static const char kPrefix[] = "CONTACT_NETWORK";
  const size_t n = sizeof kPrefix - 1;
  if (!cmname || cmname_length < n) return 0;
  for (size_t i = 0; i < n; ++i)
    if (std::toupper(static_cast<unsigned char>(cmname[i])) != kPrefix[i]) return 0;
  return 1;
}

void sffcal_umat_network(double* stress, double* statev, double* ddsdde, double* /*sse*/,
                         double* /*spd*/, double* /*scd*/, double* /*rpl*/, double* /*ddsddt*/,
                         double* /*drplde*/, double* /*drpldt*/, const double* /*stran*/,
                         const double* dstran, const double* /*time*/, const double* /*dtime*/,
                         const double* /*temp*/, const double* /*dtemp*/,
                         const double* /*predef*/, const double* /*dpred*/,
                         const char* /*cmname*/, const int* ndi, const int* nshr,
                         const int* ntens, const int* nstatv, const double* props,
                         const int* nprops, const double* /*coords*/, const double* /*drot*/,
                         double* pnewdt, const double* /*celent*/, const double* /*dfgrd0*/,
                         const double* /*dfgrd1*/, const int* noel, const int* npt,
                         const int* /*layer*/, const int* /*kspt*/, const int* /*kstep*/,
                         const int* /*kinc*/, size_t /*cmname_length*/) {
  model::umat_detail::last_message().clear();
  const int n = *ntens;
  try {
    model::umat_detail::check_layout(*ndi, *nshr, n, *nstatv, SFFCAL_UMAT_NETWORK_NSTATV);
    if (*nprops < SFFCAL_UMAT_NETWORK_NPROPS_STATE)
      throw std::runtime_error("NPROPS = " + std::to_string(*nprops) +
                               ": PROPS(1..20) must give e_0, Z_0, A_0, F_0 and F^t_0");
    const Material material = material_from_props(props, *nprops);
    net::validate(material.parameters);  // throws, naming the parameter
    const net::State<double> start =
        statev[SFFCAL_UMAT_NETWORK_STATE_INITIALISED] == 0.0
            ? initial_state(props, from_abaqus(stress, n, -1.0, 1.0), material.youngs_modulus)
            : state_from_statev(statev);
    const Eigen::Matrix3d increment = from_abaqus(dstran, n, -1.0, 0.5);  // compression positive
    const net::UpdateResult update =
        net::update_with_tangent(material.parameters, start, increment, material.youngs_modulus);
    if (!update.ok) {
      for (int i = 0; i < n * n; ++i) ddsdde[i] = 0.0;
      report(update.message, noel, npt, pnewdt);
      return;
    }
    to_abaqus(net::stress(update.end, material.youngs_modulus), stress, n, -1.0);
    model::umat_detail::to_ddsdde(update.tangent, ddsdde, n);
    statev[SFFCAL_UMAT_NETWORK_STATE_INITIALISED] = 1.0;
    state_to_statev(update.end, statev);
    statev[SFFCAL_UMAT_NETWORK_STATE_SUBSTEPS] = static_cast<double>(update.substeps);
  } catch (const std::exception& e) {
    for (int i = 0; i < n * n; ++i) ddsdde[i] = 0.0;
    report(e.what(), noel, npt, pnewdt);
  }
}

}  // extern "C"
