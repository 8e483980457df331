// The model interface (model/descriptor.h): the registry, the layouts against the UMAT headers,
// the third model (linear elasticity) through the parameter file, its Behaviour and the UMAT with
// analytic answers, and the rotation of a state (DROT) for the two fitted models.
#include "model/descriptor.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "model/parameter_file.h"
#include "model/umat.h"
#include "model/umat_network.h"

extern "C" void umat_(double*, double*, double*, double*, double*, double*, double*, double*,
                      double*, double*, const double*, const double*, const double*,
                      const double*, const double*, const double*, const double*, const double*,
                      const char*, const int*, const int*, const int*, const int*, const double*,
                      const int*, const double*, const double*, double*, const double*,
                      const double*, const double*, const int*, const int*, const int*,
                      const int*, const int*, const int*, size_t);

namespace model {
namespace {

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "descriptor_" + std::to_string(::getpid()) + "_" + name;
}

// One UMAT integration point, called as Abaqus/Standard calls umat_ (NDI 3, NSHR 3).
struct Point {
  std::string name;
  std::vector<double> props;
  double stress[6] = {0, 0, 0, 0, 0, 0};
  double statev[64] = {};
  double ddsdde[36] = {};
  double pnewdt = 1.0;
  double pnewdt_in = 1.0;  // PNEWDT on entry: 1 as Abaqus passes it, -1 as CalculiX does
  // Calls umat_ with the strain increment (tension positive, engineering shear) and the
  // rotation increment DROT (row-major here, passed column by column as Fortran stores it).
  void call(const double* dstran, const Eigen::Matrix3d& drot = Eigen::Matrix3d::Identity()) {
    double zero[64] = {}, rot[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) rot[i + 3 * j] = drot(i, j);
    int ndi = 3, nshr = 3, ntens = 6, nstatv = 64, nprops = static_cast<int>(props.size());
    int one = 1;
    pnewdt = pnewdt_in;
    umat_(stress, statev, ddsdde, zero, zero, zero, zero, zero, zero, zero, zero, dstran, zero,
          zero, zero, zero, zero, zero, name.c_str(), &ndi, &nshr, &ntens, &nstatv, props.data(),
          &nprops, zero, rot, &pnewdt, zero, rot, rot, &one, &one, &one, &one, &one, &one,
          name.size());
  }
  Eigen::Matrix3d stress_tensor() const {  // tension positive
    Eigen::Matrix3d s;
    s << stress[0], stress[3], stress[4], stress[3], stress[1], stress[5], stress[4], stress[5],
        stress[2];
    return s;
  }
};

TEST(ModelInterface, TheRegistryListsTheThreeModelsAndNamesAnUnknownOne) {
  std::vector<std::string> names;
  for (const ModelDescription* m : registered_models()) names.push_back(m->name());
  EXPECT_EQ(names, (std::vector<std::string>{"acst", "contact_network", "linear_elastic"}));
  EXPECT_EQ(find_model("contact_network").umat_name(), "CONTACT_NETWORK");
  try {
    find_model("hypoplastic");
    ADD_FAILURE() << "an unknown model was found";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'hypoplastic'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("linear_elastic"), std::string::npos) << e.what();
  }
}

// The layouts the descriptions give are the ones model/umat.h and model/umat_network.h document
// (STATEV(1) is the UMAT's own flag).
TEST(ModelInterface, TheStateLayoutsAreTheDocumentedStatev) {
  const ModelDescription& acst = find_model("acst");
  EXPECT_EQ(1 + slot_components(acst.state()), SFFCAL_UMAT_NSTATV);
  EXPECT_EQ(1 + slot_offset(acst.state(), "alpha"), SFFCAL_UMAT_STATE_ALPHA);
  EXPECT_EQ(1 + slot_offset(acst.state(), "alpha_in"), SFFCAL_UMAT_STATE_ALPHA_IN);
  EXPECT_EQ(1 + slot_offset(acst.state(), "fabric"), SFFCAL_UMAT_STATE_FABRIC);
  EXPECT_EQ(1 + slot_offset(acst.state(), "status"), SFFCAL_UMAT_STATE_STATUS);
  EXPECT_EQ(1 + slot_offset(acst.state(), "substeps"), SFFCAL_UMAT_STATE_SUBSTEPS);
  EXPECT_EQ(slot_components(acst.initial_inputs()), SFFCAL_UMAT_NPROPS_STATE);
  EXPECT_EQ(slot_components(acst.initial_inputs()) + static_cast<int>(acst.parameters().size()),
            SFFCAL_UMAT_NPROPS_MAX);
  const ModelDescription& net = find_model("contact_network");
  EXPECT_EQ(1 + slot_components(net.state()), SFFCAL_UMAT_NETWORK_NSTATV);
  EXPECT_EQ(1 + slot_offset(net.state(), "lambda"), SFFCAL_UMAT_NETWORK_STATE_LAMBDA);
  EXPECT_EQ(1 + slot_offset(net.state(), "tangential"), SFFCAL_UMAT_NETWORK_STATE_TANGENTIAL);
  EXPECT_EQ(1 + slot_offset(net.state(), "substeps"), SFFCAL_UMAT_NETWORK_STATE_SUBSTEPS);
  EXPECT_EQ(1 + slot_offset(net.state(), "inherent"), SFFCAL_UMAT_NETWORK_STATE_INHERENT);
  EXPECT_EQ(slot_components(net.initial_inputs()), SFFCAL_UMAT_NETWORK_NPROPS_STATE);
  EXPECT_EQ(slot_components(net.initial_inputs()) + 1 + static_cast<int>(net.parameters().size()),
            SFFCAL_UMAT_NETWORK_NPROPS_MAX);
}

// The third model through the one parameter-file reader and writer, with no code of its own.
TEST(ModelInterface, TheThirdModelsParameterFileRoundTripsAndIsChecked) {
  const std::string path = temp_path("elastic.json");
  write_parameter_file(path, {"linear_elastic", {}, {2.5e8, 0.2}}, {}, R"({"note": "test"})");
  const ParameterValues read = read_parameter_file(path);
  EXPECT_EQ(read.model, "linear_elastic");
  EXPECT_EQ(read.parameters, (std::vector<double>{2.5e8, 0.2}));
  EXPECT_EQ(parameter_file_model(path), "linear_elastic");
  {
    std::ofstream out(path);
    out << R"({"model": "linear_elastic", "parameters": {"youngs_modulus": {"value": 1e8,
             "unit": "Pa"}, "poissons_ratio": {"value": 0.5, "unit": "1"}}})";
  }
  try {
    read_parameter_file(path);
    ADD_FAILURE() << "nu = 0.5 accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'poissons_ratio'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("(-1, 0.5)"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_parameter_file(path, "acst"), std::runtime_error);  // another model's file
  std::remove(path.c_str());
}

// sigma = sigma_0 + lambda tr(de) I + 2 mu de, and its tangent, against the closed form.
TEST(ModelInterface, TheThirdModelsBehaviourIsLinearElasticity) {
  const double E = 2e8, nu = 0.25;
  const auto b = find_model("linear_elastic").make({}, {E, nu});
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  Eigen::Matrix3d s0 = 1e5 * Eigen::Matrix3d::Identity(), de;
  de << 1e-4, 2e-5, 0, 2e-5, -3e-5, 1e-5, 0, 1e-5, 4e-5;
  EXPECT_EQ(b->initial_state(s0, nullptr, nullptr), s0);
  const PointUpdate u = b->update(s0, nullptr, de, nullptr);
  ASSERT_EQ(u.status, UpdateStatus::kOk);
  const Eigen::Matrix3d expected =
      s0 + lambda * de.trace() * Eigen::Matrix3d::Identity() + 2 * mu * de;
  EXPECT_LT((u.stress - expected).norm(), 1e-9 * expected.norm());
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double ds = 0.0;  // d sigma_ij = D(ij, kl) de_kl over all nine kl
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) ds += u.tangent(3 * i + j, 3 * k + l) * de(k, l);
      EXPECT_NEAR(ds, expected(i, j) - s0(i, j), 1e-9 * expected.norm());
    }
}

// The third model through the UMAT (umat_, the name LINEAR_ELASTIC...): PROPS = E, nu; no state.
TEST(ModelInterface, TheThirdModelRunsThroughTheUmat) {
  const double E = 2e8, nu = 0.25, G = E / (2 * (1 + nu));
  Point pt{"LINEAR_ELASTIC-SAND", {E, nu}};
  for (int i = 0; i < 3; ++i) pt.stress[i] = -1e5;
  const double dstran[6] = {0, 0, -1e-4, 2e-5, 0, 0};  // axial compression, gamma_12
  pt.call(dstran);
  EXPECT_EQ(pt.pnewdt, 1.0) << sffcal_umat_last_message();
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  EXPECT_NEAR(pt.stress[2], -1e5 - (lambda + 2 * G) * 1e-4, 1e-6);
  EXPECT_NEAR(pt.stress[0], -1e5 - lambda * 1e-4, 1e-6);
  EXPECT_NEAR(pt.stress[3], G * 2e-5, 1e-9);  // engineering shear: sigma_12 = G gamma_12
  EXPECT_NEAR(pt.ddsdde[3 + 6 * 3], G, 1e-6);
  EXPECT_NEAR(pt.ddsdde[0 + 6 * 2], lambda, 1e-6);
  EXPECT_EQ(pt.statev[0], 1.0);
  // A Poisson's ratio of 0.5 in PROPS(2): refused by name, STRESS unchanged.
  Point bad{"linear_elastic", {E, 0.5}};
  bad.call(dstran);
  EXPECT_LE(bad.pnewdt, 0.5);
  EXPECT_NE(std::string(sffcal_umat_last_message()).find("PROPS(2)"), std::string::npos)
      << sffcal_umat_last_message();
  EXPECT_EQ(bad.stress[2], 0.0);
}

// PNEWDT as FE codes pass it: a value <= 0 on entry (CalculiX's -1) is no request of the code's
// own, so a failure asks for a smaller increment all the same, and a clean update leaves it.
// A caller's NTENS that is no layout (negative, zero, huge) is refused by name through PNEWDT, and
// nothing is written past the arrays a 3D element passes (they are guarded by sentinels here).
TEST(ModelInterface, AnNtensThatIsNoLayoutIsRefusedWithoutWritingPastTheArrays) {
  for (int ntens : {-100, -1, 0, 5, 1000000}) {
    double stress[6 + 2] = {}, ddsdde[36 + 2], statev[32] = {}, zero[64] = {}, rot[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (double& x : ddsdde) x = 7.0;  // sentinels
    const std::vector<double> props = {2.5e8, 0.2};
    int ndi = 3, nshr = 3, nstatv = 32, nprops = 2, one = 1;
    double pnewdt = 1.0;
    const std::string name = "LINEAR_ELASTIC";
    umat_(stress, statev, ddsdde, zero, zero, zero, zero, zero, zero, zero, zero, zero, zero, zero,
          zero, zero, zero, zero, name.c_str(), &ndi, &nshr, &ntens, &nstatv, props.data(), &nprops,
          zero, rot, &pnewdt, zero, rot, rot, &one, &one, &one, &one, &one, &one, name.size());
    EXPECT_LE(pnewdt, 0.5) << "NTENS " << ntens;
    for (double x : ddsdde) EXPECT_EQ(x, 7.0) << "NTENS " << ntens;
    EXPECT_NE(std::string(sffcal_umat_last_message()).find("NTENS"), std::string::npos)
        << sffcal_umat_last_message();
  }
}

TEST(ModelInterface, AFailureAsksForASmallerIncrementWhateverPnewdtCameIn) {
  Point pt{"LINEAR_ELASTIC", {2e8, 0.25}};
  pt.pnewdt_in = -1.0;
  const double dstran[6] = {0, 0, -1e-4, 0, 0, 0};
  pt.call(dstran);
  EXPECT_EQ(pt.pnewdt, -1.0);
  Point bad{"LINEAR_ELASTIC", {2e8, 0.7}};
  bad.pnewdt_in = -1.0;
  bad.call(dstran);
  EXPECT_EQ(bad.pnewdt, 0.5) << sffcal_umat_last_message();
  bad.pnewdt_in = 0.2;  // an FE code's own smaller request is kept
  bad.call(dstran);
  EXPECT_EQ(bad.pnewdt, 0.2);
}

// A NaN or infinite STRESS, DSTRAN, STATEV or DROT, and an answer that is not finite (a strain
// increment of 1e300 through linear elasticity), are refused by name with a cut step, STRESS and
// STATEV left as they came (found by fuzz/umat_fuzzer.cc: linear elasticity returned a NaN
// strain increment as a clean update of NaN stress).
TEST(ModelInterface, ANonFiniteInputOrAnswerIsRefusedWithACutStep) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    double stress_11, dstran_33;
    const char* fragment;
  };
  for (const Case& c : {Case{-1e5, nan, "DSTRAN(3)"}, Case{inf, -1e-4, "STRESS(1)"},
                        Case{-1e5, -1e300, "not finite"}}) {
    Point pt{"LINEAR_ELASTIC", {2e8, 0.25}};
    pt.stress[0] = c.stress_11;
    pt.stress[1] = pt.stress[2] = -1e5;
    const double dstran[6] = {0, 0, c.dstran_33, 0, 0, 0};
    pt.call(dstran);
    EXPECT_EQ(pt.pnewdt, 0.5) << c.fragment;
    EXPECT_NE(std::string(sffcal_umat_last_message()).find(c.fragment), std::string::npos)
        << sffcal_umat_last_message();
    EXPECT_EQ(pt.stress[2], -1e5);
    EXPECT_EQ(pt.statev[0], 0.0);
  }
  // After the first increment (STATEV(1) = 1): a NaN in STATEV, or in DROT.
  const double dstran[6] = {0, 0, -1e-4, 0, 0, 0};
  Point bad_state{"LINEAR_ELASTIC", {2e8, 0.25}};
  bad_state.statev[0] = nan;
  bad_state.call(dstran);
  EXPECT_EQ(bad_state.pnewdt, 0.5);
  EXPECT_NE(std::string(sffcal_umat_last_message()).find("STATEV(1)"), std::string::npos)
      << sffcal_umat_last_message();
  EXPECT_EQ(bad_state.stress[2], 0.0);
  Point bad_rotation{"LINEAR_ELASTIC", {2e8, 0.25}};
  bad_rotation.statev[0] = 1.0;
  Eigen::Matrix3d drot = Eigen::Matrix3d::Identity();
  drot(1, 0) = nan;
  bad_rotation.call(dstran, drot);
  EXPECT_EQ(bad_rotation.pnewdt, 0.5);
  EXPECT_NE(std::string(sffcal_umat_last_message()).find("DROT(2)"), std::string::npos)
      << sffcal_umat_last_message();
}

Eigen::Matrix3d rotation_about_3(double angle) {
  Eigen::Matrix3d r;
  r << std::cos(angle), -std::sin(angle), 0, std::sin(angle), std::cos(angle), 0, 0, 0, 1;
  return r;
}

// DROT = 90 degrees about axis 3 and no strain: the contact-network model, whose stress is the
// SFF equation of its (anisotropic) state, returns R sigma R^T; without the rotation of its
// tensors it would return sigma.
TEST(ModelInterface, ARotatedNetworkStateGivesTheRotatedStress) {
  std::vector<double> props(48, 0.0);
  props[0] = 0.62, props[1] = 5.5;
  const double a[6] = {-0.04, 0.08, -0.04, 0.01, 0.0, 0.0}, f[6] = {-0.05, 0.1, -0.05, 0, 0.01, 0};
  for (int k = 0; k < 6; ++k) props[2 + k] = a[k], props[8 + k] = f[k], props[14 + k] = 0.2 * f[k];
  props[20] = 150e6;
  const double par[27] = {300, 4.6, 0.2, 20, 5, 0.6, 0.3, 30, 0.7, 0.4, 40, 0.1, 0.05, 50,
                          2,   1,   1,   0.5, 0.8, 0.5, 0.7, 2, 0.8, 0.05, 1, 0.5, 0.5};
  for (int k = 0; k < 27; ++k) props[21 + k] = par[k];
  Point pt{"CONTACT_NETWORK", props};
  for (int i = 0; i < 3; ++i) pt.stress[i] = -1e5;
  const double none[6] = {0, 0, 0, 0, 0, 0};
  pt.call(none);
  ASSERT_EQ(pt.pnewdt, 1.0) << sffcal_umat_last_message();
  const Eigen::Matrix3d before = pt.stress_tensor();
  ASSERT_GT(std::abs(before(1, 1) - before(0, 0)), 1e3);  // anisotropic
  const Eigen::Matrix3d r = rotation_about_3(M_PI / 2);
  pt.call(none, r);
  ASSERT_EQ(pt.pnewdt, 1.0) << sffcal_umat_last_message();
  EXPECT_LT((pt.stress_tensor() - r * before * r.transpose()).norm(), 1e-9 * before.norm());
  // An initial input that is not physical is named by its PROPS: F_0 with a trace, PROPS(9..14).
  Point bad{"CONTACT_NETWORK", props};
  for (int i = 0; i < 3; ++i) bad.stress[i] = -1e5;
  bad.props[8] = 0.3;
  bad.call(none);
  EXPECT_LE(bad.pnewdt, 0.5);
  EXPECT_NE(std::string(sffcal_umat_last_message()).find("PROPS(9..14)"), std::string::npos)
      << sffcal_umat_last_message();
}

// ACST carries its stress in STRESS (rotated by the FE code) and its tensors in STATEV: after a
// rotation R, an increment R de R^T gives R sigma(de) R^T, the response of the unrotated point.
TEST(ModelInterface, ARotatedAcstStateRespondsAsTheRotatedMaterial) {
  std::vector<double> props = {0.8,  -0.05, 0.1,  -0.05, 0.02, 0.0,  0.0,   125,   0.05,
                               1.25, 0.712, 0.934, 0.019, 0.7, 0.01, 7.05,  0.968, 1.1,
                               0.704, 3.5,  0.1,  5.0};
  const double first[6] = {1e-4, 1e-4, -4e-4, 0, 0, 0};
  Point pt{"SAND", props};
  for (int i = 0; i < 3; ++i) pt.stress[i] = -1e5;
  pt.call(first);
  ASSERT_EQ(pt.pnewdt, 1.0) << sffcal_umat_last_message();
  const Eigen::Matrix3d r = rotation_about_3(0.3);
  Eigen::Matrix3d de;  // tension positive, tensor shear
  de << 1e-4, 3e-5, 0, 3e-5, -2e-4, 0, 0, 0, 5e-5;
  auto engineering = [](const Eigen::Matrix3d& e, double* v) {
    v[0] = e(0, 0), v[1] = e(1, 1), v[2] = e(2, 2);
    v[3] = 2 * e(0, 1), v[4] = 2 * e(0, 2), v[5] = 2 * e(1, 2);
  };
  double d[6], d_rotated[6];
  engineering(de, d);
  engineering(r * de * r.transpose(), d_rotated);
  Point unrotated = pt, rotated = pt;
  unrotated.call(d);
  // STRESS as the FE code turns it.
  const Eigen::Matrix3d s = r * pt.stress_tensor() * r.transpose();
  rotated.stress[0] = s(0, 0), rotated.stress[1] = s(1, 1), rotated.stress[2] = s(2, 2);
  rotated.stress[3] = s(0, 1), rotated.stress[4] = s(0, 2), rotated.stress[5] = s(1, 2);
  rotated.call(d_rotated, r);
  ASSERT_EQ(unrotated.pnewdt, 1.0) << sffcal_umat_last_message();
  ASSERT_EQ(rotated.pnewdt, 1.0) << sffcal_umat_last_message();
  const Eigen::Matrix3d expected = r * unrotated.stress_tensor() * r.transpose();
  EXPECT_LT((rotated.stress_tensor() - expected).norm(), 1e-8 * expected.norm());
  // Without DROT the fabric and back-stress stay in the old axes: a different answer.
  Point stale = pt;
  stale.stress[0] = s(0, 0), stale.stress[1] = s(1, 1), stale.stress[2] = s(2, 2);
  stale.stress[3] = s(0, 1), stale.stress[4] = s(0, 2), stale.stress[5] = s(1, 2);
  stale.call(d_rotated);
  EXPECT_GT((stale.stress_tensor() - expected).norm(), 1e-6 * expected.norm());
}

}  // namespace
}  // namespace model
