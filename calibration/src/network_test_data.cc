// A DEM test as the contact-network model reads it (network_test_data.h).
#include "calibration/network_test_data.h"

#include <stdexcept>
#include <string>

#include "model/network_path.h"
#include "sff/sff_equation.h"

namespace calibration::network {

using model::network::axisymmetric;
using model::network::State;

TestData with_closing_normal_anisotropy(TestData t) {
  if (t.snapshot_eta.size() != t.a_n.size() || t.a_c.size() != t.a_n.size() ||
      t.a_t.size() != t.a_n.size())
    throw std::runtime_error("test '" + t.name + "' (" + t.source +
                             "): its SFF table lacks the contacts' stress ratio eta or a_t at "
                             "some snapshot, from which the contact-network model's a_n is found "
                             "(run `sffcal sff` again)");
  for (std::size_t k = 0; k < t.a_n.size(); ++k) {
    try {
      t.a_n[k] = sff::concise_normal_anisotropy(t.a_c[k], t.a_t[k], t.snapshot_eta[k]);
    } catch (const sff::StatisticsError& e) {
      throw std::runtime_error("test '" + t.name + "' (" + t.source + "), snapshot " +
                               std::to_string(k) + ": " + e.what());
    }
  }
  t.normal_anisotropy = "closing";
  return t;
}

State<double> initial_state(const TestData& t) {
  if (t.coordination.empty() || t.lambda.empty() || t.a_t.empty())
    throw std::runtime_error("test '" + t.name + "' (" + t.source +
                             "): its SFF table has no coordination, lambda or a_t, which the "
                             "contact-network model starts from (run `sffcal sff` again)");
  return {t.e0,
          t.coordination.front(),
          t.lambda.front(),
          axisymmetric(t.a_c.front()),
          axisymmetric(t.a_n.front()),
          axisymmetric(t.a_t.front()),
          axisymmetric(t.a_c.front())};  // the whole initial fabric is the specimen's own (N2d)
}

}  // namespace calibration::network
