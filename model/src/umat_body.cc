// The UMAT body of every registered model (umat_common.h): PROPS and STATEV laid out from the
// model's description (descriptor.h), its Behaviour called once per increment, the step cut
// through PNEWDT. model/umat.h and model/umat_network.h state the two fitted models' layouts.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/descriptor.h"
#include "model/parameter_file.h"
#include "umat_common.h"

namespace model::umat_detail {

namespace {

// "PROPS(k)" or "PROPS(a..b)" for zero-based components [first, first + count).
std::string props_name(int first, int count) {
  return "PROPS(" + std::to_string(first + 1) +
         (count > 1 ? ".." + std::to_string(first + count) : std::string()) + ")";
}

// The values of the parameter file named by the model's environment variable, read once per path
// (thread-safe).
ParameterValues values_from_file(const ModelDescription& d, int first_props) {
  const std::string variable = d.parameter_file_variable();
  const char* path = std::getenv(variable.c_str());
  if (!path || !*path)
    throw std::runtime_error("NPROPS = " + std::to_string(first_props) +
                             " and no parameter file: set " + variable + " to the " + d.name() +
                             " parameter file (JSON), or give the values in PROPS(" +
                             std::to_string(first_props + 1) + "..)");
  static std::mutex mutex;
  static std::map<std::string, ParameterValues> read;
  static std::map<std::string, std::string> errors;
  const std::lock_guard<std::mutex> lock(mutex);
  const std::string key = d.name() + '\n' + path;
  if (!read.count(key) && !errors.count(key)) {
    try {
      read[key] = read_parameter_file(path, d.name());
    } catch (const std::exception& e) {
      errors[key] = e.what();
    }
  }
  if (errors.count(key)) throw std::runtime_error(errors[key]);
  return read[key];
}

// The constants and parameters from PROPS after the initial inputs: the non-fixed constants, the
// parameters every file gives, then those added later where NPROPS reaches them.
ParameterValues values_from_props(const ModelDescription& d, const double* props, int nprops,
                                  int first) {
  int required = 0, given_constants = 0;
  for (const ParameterInfo& p : d.parameters()) required += p.required() ? 1 : 0;
  for (const ParameterInfo& c : d.constants()) given_constants += c.fixed() ? 0 : 1;
  const int least = first + given_constants + required;
  const int most = first + given_constants + static_cast<int>(d.parameters().size());
  if (nprops < least || nprops > most)
    throw std::runtime_error("NPROPS = " + std::to_string(nprops) + ": give " +
                             std::to_string(first) + " (the initial state; the rest from " +
                             d.parameter_file_variable() + ") or " + std::to_string(least) +
                             " to " + std::to_string(most) +
                             " (with the constants and parameters in PROPS(" +
                             std::to_string(first + 1) + "..), those after PROPS(" +
                             std::to_string(least) + ") at the values that leave them out)");
  ParameterValues values{d.name(), {}, {}};
  int k = first;
  auto take = [&](const ParameterInfo& info, int index) {
    if (index >= nprops) return info.value_if_absent;
    const double x = props[index];
    if (!std::isfinite(x) || !info.physical.contains(x))
      throw std::runtime_error(props_name(index, 1) + ", '" + info.name + "' = " +
                               format_number(x) +
                               (std::string(info.unit) == "1" ? "" : std::string(" ") + info.unit) +
                               ", is not physical: it must be " + info.physical.describe());
    return x;
  };
  for (const ParameterInfo& c : d.constants())
    values.constants.push_back(c.fixed() ? c.physical.low : take(c, k++));
  for (const ParameterInfo& p : d.parameters()) values.parameters.push_back(take(p, k++));
  return values;
}

// The behaviour for the values PROPS (or the parameter file) give, made and validated once per
// thread for as long as they stay the same: FE codes call the UMAT with the same PROPS at every
// point of a material, and making it at every call cost 3-10 % of an update.
const Behaviour& behaviour_for(const ModelDescription& d, const double* props, int nprops,
                               int inputs) {
  struct Cache {
    const ModelDescription* model = nullptr;
    std::string file;           // the parameter file's path where PROPS give the inputs alone
    std::vector<double> given;  // PROPS after the initial inputs
    std::unique_ptr<Behaviour> behaviour;
  };
  thread_local Cache cache;
  const char* path = nprops == inputs ? std::getenv(d.parameter_file_variable().c_str()) : nullptr;
  const std::string file = path ? path : "";
  const std::size_t n = static_cast<std::size_t>(nprops - inputs);
  if (cache.model == &d && cache.behaviour && cache.file == file && cache.given.size() == n &&
      std::equal(props + inputs, props + nprops, cache.given.begin()))
    return *cache.behaviour;
  const ParameterValues values =
      nprops == inputs ? values_from_file(d, inputs) : values_from_props(d, props, nprops, inputs);
  cache.behaviour = d.make(values.constants, values.parameters);
  cache.model = &d;
  cache.file = file;
  cache.given.assign(props + inputs, props + nprops);
  return *cache.behaviour;
}

// Throws std::runtime_error naming the first of the n values of the UMAT argument `name` that is
// not finite (numbered from 1, as the FE code numbers it).
void require_finite(const double* v, int n, const char* name) {
  for (int k = 0; k < n; ++k)
    if (!std::isfinite(v[k]))
      throw std::runtime_error(std::string(name) + "(" + std::to_string(k + 1) + ") = " +
                               std::to_string(v[k]) + " is not finite");
}

// The 3x3 matrix of DROT (Fortran order, column by column).
Eigen::Matrix3d rotation_of(const double* drot) {
  Eigen::Matrix3d r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = drot[i + 3 * j];
  return r;
}

}  // namespace

const ModelDescription& umat_model(const char* cmname, std::size_t cmname_length) {
  for (const ModelDescription* m : registered_models()) {
    const std::string prefix = m->umat_name();
    if (m->name() == "acst" || cmname_length < prefix.size() || !cmname) continue;
    bool same = true;
    for (std::size_t i = 0; i < prefix.size() && same; ++i)
      same = std::toupper(static_cast<unsigned char>(cmname[i])) == prefix[i];
    if (same) return *m;
  }
  return find_model("acst");  // any other name, as before the other models existed
}

void umat_body(const ModelDescription& d, double* stress, double* statev, double* ddsdde,
               const double* dstran, const int* ndi, const int* nshr, const int* ntens,
               const int* nstatv, const double* props, const int* nprops, const double* drot,
               double* pnewdt, const int* noel, const int* npt) {
  last_message().clear();
  const int n = *ntens;
  const int inputs = slot_components(d.initial_inputs());
  const int state_size = slot_components(d.state());
  try {
    check_layout(*ndi, *nshr, n, *nstatv, 1 + state_size);
    if (*nprops < inputs) {
      std::string names;
      for (const Slot& s : d.initial_inputs())
        names += (names.empty() ? "" : ", ") + std::string(s.name);
      throw std::runtime_error("NPROPS = " + std::to_string(*nprops) + ": " +
                               props_name(0, inputs) + " must give the initial " + names);
    }
    const Behaviour& behaviour = behaviour_for(d, props, *nprops, inputs);
    // A NaN or infinite input would come back as a clean update of NaN (linear elasticity passes
    // it through): refused like a bad PROPS.
    require_finite(stress, n, "STRESS");
    require_finite(dstran, n, "DSTRAN");

    const Eigen::Matrix3d start_stress = from_abaqus(stress, n, -1.0, 1.0);  // compression +
    thread_local std::vector<double> start, end;
    start.assign(static_cast<std::size_t>(state_size), 0.0);
    end.assign(static_cast<std::size_t>(state_size), 0.0);
    Eigen::Matrix3d sigma = start_stress;
    if (statev[0] == 0.0) {
      try {
        sigma = behaviour.initial_state(start_stress, props, start.data());
      } catch (const InvalidInput& e) {  // named by its PROPS
        int offset = 0;
        for (const Slot& slot : d.initial_inputs()) {
          if (e.slot() == slot.name)
            throw std::runtime_error(props_name(offset, slot.size()) + ": " + e.what());
          offset += slot.size();
        }
        throw;
      }
    } else {
      require_finite(statev, 1 + state_size, "STATEV");
      require_finite(drot, 9, "DROT");
      std::copy(statev + 1, statev + 1 + state_size, start.begin());
      const Eigen::Matrix3d r = rotation_of(drot);
      if (!r.isIdentity(0.0)) rotate_state(d.state(), r, start.data());  // NLGEOM's DROT
    }
    const Eigen::Matrix3d increment = from_abaqus(dstran, n, -1.0, 0.5);
    const PointUpdate update = behaviour.update(sigma, start.data(), increment, end.data());
    to_ddsdde(update.tangent, ddsdde, n);
    if (update.status == UpdateStatus::kFailed) {
      report("update failed: " + update.message, noel, npt, pnewdt, update.step_ratio);
      return;
    }
    // An answer that is not finite (finite inputs far out of range: a strain increment of 1e300)
    // is a failed update whatever the model says: STRESS and STATEV are left as they came, and
    // DDSDDE is zero, as for a refused input (its tangent belongs to an answer not taken).
    if (!update.stress.allFinite() || !update.tangent.allFinite() ||
        !std::all_of(end.begin(), end.end(), [](double x) { return std::isfinite(x); })) {
      std::fill(ddsdde, ddsdde + n * n, 0.0);
      report("update failed: its stress, tangent or state is not finite", noel, npt, pnewdt);
      return;
    }
    to_abaqus(update.stress, stress, n, -1.0);
    statev[0] = 1.0;
    std::copy(end.begin(), end.end(), statev + 1);
    if (update.status == UpdateStatus::kUnreliable)
      report("unreliable update: " + update.message, noel, npt, pnewdt, update.step_ratio);
  } catch (const std::exception& e) {
    // DDSDDE is NTENS x NTENS only where NTENS is a layout the check accepts: a caller's NTENS of
    // -100 must not become 10,000 writes.
    if (n == 4 || n == 6)
      for (int i = 0; i < n * n; ++i) ddsdde[i] = 0.0;
    report(d.umat_name() + ": " + e.what(), noel, npt, pnewdt);
  }
}

}  // namespace model::umat_detail
