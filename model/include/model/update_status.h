// The outcome of a constitutive update, one type for every model (ACST, the contact-network model)
// and for the FE material interface that adapts them (fe_model::MaterialStatus), in the order of
// MGIS' integrate() results 1 / 0 / -1 (ok / unreliable / failed).
#pragma once

namespace model {

enum class UpdateStatus {
  kOk,          ///< integrated to the model's tolerance
  kUnreliable,  ///< integrated over the whole increment, its accuracy doubtful: cut the step
  kFailed,      ///< not integrated, no usable result (the reason is reported beside it)
};

/// "ok", "unreliable" or "failed".
const char* to_string(UpdateStatus status);

/// The worse of two statuses (failed > unreliable > ok).
UpdateStatus worst(UpdateStatus a, UpdateStatus b);

}  // namespace model
