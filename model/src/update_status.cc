// The shared update status (update_status.h).
#include "model/update_status.h"

namespace model {

const char* to_string(UpdateStatus status) {
  switch (status) {
    case UpdateStatus::kOk:
      return "ok";
    case UpdateStatus::kUnreliable:
      return "unreliable";
    case UpdateStatus::kFailed:
      return "failed";
  }
  return "unknown";
}

UpdateStatus worst(UpdateStatus a, UpdateStatus b) {
  return static_cast<int>(a) > static_cast<int>(b) ? a : b;
}

}  // namespace model
