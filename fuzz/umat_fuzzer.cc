// Fuzz target: the UMAT entries (model/umat.h, model/umat_network.h, and umat_, the Fortran name
// of libsffcal_umat.so that dispatches on CMNAME), called as an FE code calls them. The bytes
// choose the entry, the material name, the counts NDI, NSHR, NTENS, NSTATV and NPROPS, PNEWDT,
// and edits of a plausible call (the model's parameters from fuzz/corpus/parameter_file, a
// compressed start, a small strain increment) that put special numbers into PROPS, STRESS,
// STATEV, DSTRAN, DROT and the scalars; then one to three increments are run.
//
// Every array is allocated at the size its count declares (Abaqus: the caller owns the sizes),
// so a write the UMAT makes past one is reported by AddressSanitizer. Bad arguments must end in
// a message (sffcal_umat_last_message) and a cut step (0 < PNEWDT < 1), never a crash; an
// increment that reports nothing must return finite STRESS, DDSDDE and state.
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "model/descriptor.h"
#include "model/parameter_file.h"
#include "model/umat.h"
#include "model/umat_network.h"
#include "special_values.h"
#include "umat_common.h"  // model/src: umat_, and the model a material name chooses

namespace {

using sffcal_fuzz::finding;
using sffcal_fuzz::special_real;

// A plausible call of one model: its PROPS (initial inputs, free constants, parameters) from the
// model's parameter file in the corpus, which its environment variable also names (NPROPS equal
// to the inputs alone reads the rest from there).
struct ModelCall {
  const model::ModelDescription* description = nullptr;
  std::vector<double> props;
  int inputs = 0;      // PROPS of the initial state
  int state_size = 0;  // STATEV(2..)
};

std::vector<ModelCall> plausible_calls() {
  std::vector<ModelCall> calls;
  for (const model::ModelDescription* d : model::registered_models()) {
    const std::string path = SFFCAL_FUZZ_DIR "/corpus/parameter_file/" + d->name() + ".json";
    ModelCall call;
    call.description = d;
    call.inputs = model::slot_components(d->initial_inputs());
    call.state_size = model::slot_components(d->state());
    std::vector<double> inputs;
    for (const model::Slot& slot : d->initial_inputs()) {
      if (slot.kind == model::Slot::kTensor) {
        inputs.insert(inputs.end(), 6, 0.0);  // an isotropic start
      } else {
        inputs.push_back(std::string(slot.name) == "coordination" ? 5.0 : 0.8);  // else e_0
      }
    }
    try {
      const model::ParameterValues values = model::read_parameter_file(path, d->name());
      call.props = model::umat_props(*d, inputs, values.constants, values.parameters);
      setenv(d->parameter_file_variable().c_str(), path.c_str(), 1);
    } catch (const std::exception& e) {
      finding("the UMAT target's parameter file of model '" + d->name() + "': " + e.what());
    }
    calls.push_back(call);
  }
  return calls;
}

// An array of exactly `count` values (none where the count is negative), for AddressSanitizer.
struct Array {
  explicit Array(int count, double fill = 0.0)
      : size(static_cast<std::size_t>(std::max(count, 0))), data(new double[size]) {
    std::fill(data.get(), data.get() + size, fill);
  }
  double& operator[](std::size_t k) { return data[k]; }
  std::size_t size;
  std::unique_ptr<double[]> data;
};

// A count: the plausible one most of the time, else any small number (negative ones included).
int count(FuzzedDataProvider& bytes, int plausible, int low, int high) {
  return bytes.ConsumeIntegralInRange<int>(0, 3) != 0 ? plausible
                                                       : bytes.ConsumeIntegralInRange(low, high);
}

bool all_finite(const double* v, std::size_t n) {
  return std::all_of(v, v + n, [](double x) { return std::isfinite(x); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::vector<ModelCall> calls = plausible_calls();
  FuzzedDataProvider bytes(data, size);

  // The entry, and the model whose plausible call is the start (umat_: any, by its name).
  const int entry = bytes.ConsumeIntegralInRange(0, 2);
  std::size_t model_index = 0;
  for (std::size_t k = 0; k < calls.size(); ++k)
    if (calls[k].description->name() == (entry == 1 ? "contact_network" : "acst")) model_index = k;
  if (entry == 2) model_index = bytes.ConsumeIntegralInRange<std::size_t>(0, calls.size() - 1);
  const ModelCall& call = calls[model_index];

  // CMNAME as Fortran passes it: blank padded, not terminated, its length last.
  std::string name = call.description->umat_name();
  switch (bytes.ConsumeIntegralInRange(0, 3)) {
    case 0: break;
    case 1: name.resize(80, ' '); break;
    case 2:
      for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      break;
    default: name = bytes.ConsumeRandomLengthString(100);
  }
  const std::unique_ptr<char[]> cmname(new char[name.size()]);
  std::memcpy(cmname.get(), name.data(), name.size());

  // The counts, and the arrays at their sizes.
  const bool plane = bytes.ConsumeBool();
  const int ndi = count(bytes, 3, -2, 8);
  const int nshr = count(bytes, plane ? 1 : 3, -2, 8);
  const int ntens = count(bytes, plane ? 4 : 6, -64, 40);
  const int nstatv = count(bytes, 1 + call.state_size + bytes.ConsumeIntegralInRange(0, 4), -8, 64);
  const int full_props = static_cast<int>(call.props.size());
  const int nprops =
      bytes.ConsumeBool() ? call.inputs : count(bytes, full_props, -8, full_props + 8);
  Array props(nprops, 1.0), stress(ntens), statev(nstatv), ddsdde(ntens * std::max(ntens, 0));
  Array stran(ntens), dstran(ntens), ddsddt(ntens), drplde(ntens);
  Array drot(9), dfgrd0(9), dfgrd1(9), coords(3), time(2), predef(1), dpred(1);
  std::copy(call.props.begin(), call.props.begin() + std::min<std::size_t>(props.size, static_cast<std::size_t>(full_props)),
            props.data.get());
  for (int k = 0; k < 3; ++k) drot[4 * k] = dfgrd0[4 * k] = dfgrd1[4 * k] = 1.0;
  for (std::size_t k = 0; k < std::min<std::size_t>(stress.size, 3); ++k) {
    stress[k] = -100e3;                      // tension positive: 100 kPa all round
    dstran[k] = k == 2 ? -1e-4 : 0.3e-4;     // axial compression, lateral swelling
  }
  double sse = 0.0, spd = 0.0, scd = 0.0, rpl = 0.0, drpldt = 0.0;
  double dtime = 1.0, temp = 293.0, dtemp = 0.0, celent = 1.0;
  double pnewdt = bytes.ConsumeBool() ? 1.0 : special_real(bytes, 1.0);  // CalculiX passes -1
  const int noel = 1, npt = 1, layer = 1, kspt = 1, kstep = 1;

  const bool verbose = sffcal_fuzz::verbose();
  if (verbose)
    std::fprintf(stderr, "  %s, CMNAME '%s', NDI %d NSHR %d NTENS %d NSTATV %d NPROPS %d, PNEWDT %g\n",
                 entry == 0 ? "sffcal_umat" : entry == 1 ? "sffcal_umat_network" : "umat_",
                 name.c_str(), ndi, nshr, ntens, nstatv, nprops, pnewdt);

  // Edits of the plausible call.
  auto edit = [&](int edits) {
    for (int e = 0; e < edits; ++e) {
      Array* arrays[] = {&props, &stress, &statev, &dstran, &drot, &stran};
      const char* names[] = {"PROPS", "STRESS", "STATEV", "DSTRAN", "DROT", "STRAN"};
      const std::size_t which = bytes.ConsumeIntegralInRange<std::size_t>(0, 5);
      Array& target = *arrays[which];
      if (target.size == 0) continue;
      const std::size_t k = bytes.ConsumeIntegralInRange<std::size_t>(0, target.size - 1);
      target[k] = special_real(bytes, target[k]);
      if (verbose) std::fprintf(stderr, "  %s(%zu) = %g\n", names[which], k + 1, target[k]);
    }
    if (bytes.ConsumeIntegralInRange(0, 7) == 0) {
      dtime = special_real(bytes, dtime);
      if (verbose) std::fprintf(stderr, "  DTIME = %g\n", dtime);
    }
  };
  edit(bytes.ConsumeIntegralInRange(0, 6));

  const int increments = bytes.ConsumeIntegralInRange(1, 3);
  for (int kinc = 1; kinc <= increments; ++kinc) {
    const double pnewdt_in = pnewdt;
    auto* umat = entry == 0 ? &sffcal_umat : entry == 1 ? &sffcal_umat_network : &umat_;
    umat(stress.data.get(), statev.data.get(), ddsdde.data.get(), &sse, &spd, &scd, &rpl,
         ddsddt.data.get(), drplde.data.get(), &drpldt, stran.data.get(), dstran.data.get(),
         time.data.get(), &dtime, &temp, &dtemp, predef.data.get(), dpred.data.get(),
         cmname.get(), &ndi, &nshr, &ntens, &nstatv, props.data.get(), &nprops, coords.data.get(),
         drot.data.get(), &pnewdt, &celent, dfgrd0.data.get(), dfgrd1.data.get(), &noel, &npt,
         &layer, &kspt, &kstep, &kinc, name.size());
    const std::string message = sffcal_umat_last_message();
    if (verbose)
      std::fprintf(stderr, "  increment %d: PNEWDT %g -> %g; %s\n", kinc, pnewdt_in, pnewdt,
                   message.empty() ? "clean" : message.c_str());
    if (!message.empty()) {
      if (!(pnewdt > 0.0 && pnewdt < 1.0))
        finding("a refused increment left PNEWDT at " + std::to_string(pnewdt) + ": " + message);
    } else {
      // A clean increment's layout was accepted, so the sizes are those of the model called.
      const model::ModelDescription& called =
          entry == 2 ? model::umat_detail::umat_model(cmname.get(), name.size())
                     : *call.description;
      const std::size_t state = static_cast<std::size_t>(1 + model::slot_components(called.state()));
      const char* bad = !all_finite(stress.data.get(), stress.size)   ? "STRESS"
                        : !all_finite(ddsdde.data.get(), ddsdde.size) ? "DDSDDE"
                        : !all_finite(statev.data.get(), std::min(state, statev.size)) ? "STATEV"
                                                                                     : nullptr;
      if (bad) finding("an increment that reported nothing returned a " + std::string(bad) +
                       " that is not finite");
    }
    pnewdt = 1.0;
    edit(bytes.ConsumeIntegralInRange(0, 2));
  }
  return 0;
}
