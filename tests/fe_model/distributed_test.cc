// The distributed mesh (DistributedSolid: p4est + Trilinos) against the one-process Solid, run
// under `mpirun -np 2` (ctest: fe_model_mpi_tests). Every process runs every test; the
// distributed run splits the cells between the processes, the serial reference is computed whole
// on each. The answers agree to the solver's tolerance (Newton to 1e-10 of the residual, GMRES to
// 1e-8): not bit for bit, because the sums over processes and the block-Jacobi preconditioner
// change the order of the operations.
#include <deal.II/base/mpi.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include "model/acst_model.h"
#include "fe_model/acst_material.h"
#include "fe_model/triaxial.h"
#include "test_materials.h"

namespace fe_model {
namespace {

constexpr double kP0 = 100e3;  // [Pa]

unsigned int n_processes() { return dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD); }

TriaxialOptions rough_mesh(unsigned int nx, unsigned int nz, double strain, unsigned int steps) {
  TriaxialOptions options;
  options.width = 0.5;
  options.height = 1.0;
  options.cells_x = options.cells_y = nx;
  options.cells_z = nz;
  options.confining_pressure = kP0;
  options.axial_strain_end = strain;
  options.n_steps = steps;
  options.rough_platens = true;
  options.solver.linear_solver = SolverOptions::LinearSolver::kIterative;
  return options;
}

// The distributed run gives the serial one's curves and bulge to `tolerance` (relative to the
// stress scale p0 + |q| and to the largest bulge).
void expect_same_answer(const TriaxialResult& serial, const TriaxialResult& distributed,
                        double tolerance) {
  ASSERT_TRUE(serial.completed) << serial.message;
  ASSERT_TRUE(distributed.completed) << distributed.message;
  ASSERT_EQ(serial.steps.size(), distributed.steps.size());
  double worst_q = 0.0, worst_v = 0.0, worst_bulge = 0.0;
  for (std::size_t i = 0; i < serial.steps.size(); ++i) {
    const TriaxialStep &a = serial.steps[i], &b = distributed.steps[i];
    const double scale = kP0 + std::abs(a.q);
    worst_q = std::max({worst_q, std::abs(b.q - a.q) / scale, std::abs(b.p - a.p) / scale});
    worst_v = std::max(worst_v, std::abs(b.volumetric_strain - a.volumetric_strain));
    EXPECT_NEAR(a.axial_strain, b.axial_strain, 1e-15) << "step " << i;
  }
  ASSERT_EQ(serial.bulge.size(), distributed.bulge.size());
  double largest = 0.0;
  for (const BulgePoint& point : serial.bulge)
    largest = std::max(largest, std::abs(point.radial_displacement));
  ASSERT_GT(largest, 0.0);
  for (std::size_t i = 0; i < serial.bulge.size(); ++i) {
    EXPECT_EQ(serial.bulge[i].z, distributed.bulge[i].z);
    worst_bulge = std::max(worst_bulge, std::abs(distributed.bulge[i].radial_displacement -
                                                 serial.bulge[i].radial_displacement) / largest);
  }
  EXPECT_LT(worst_q, tolerance);
  EXPECT_LT(worst_v, tolerance);
  EXPECT_LT(worst_bulge, tolerance);
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << n_processes() << " processes against 1: largest |dq|/(p0 + |q|) " << worst_q
            << ", |d eps_v| " << worst_v << ", |d bulge|/max " << worst_bulge << '\n';
}

TEST(DistributedTriaxial, RunsOnSeveralProcesses) { EXPECT_GE(n_processes(), 2u); }

// A nonlinear elastic law on a bulging mesh: the same curves and bulge.
TEST(DistributedTriaxial, GivesTheSerialAnswerForANonlinearLaw) {
  const testing::HypoelasticTestMaterial material(0.01, 60.0);
  TriaxialOptions options = rough_mesh(3, 4, 0.02, 4);
  const TriaxialResult serial = run_triaxial(material, options);
  options.distributed = true;
  const TriaxialResult distributed = run_triaxial(material, options);
  expect_same_answer(serial, distributed, 1e-8);
}

// The ACST model (elastic cone crossing, plastic flow, dilatancy) on a bulging mesh.
TEST(DistributedTriaxial, GivesTheSerialAnswerForTheAcstModel) {
  const model::acst::Parameters<double> parameters = model::acst::read_parameters_json(
      std::string(SFFCAL_SOURCE_DIR) + "/examples/acst_toyoura.json");
  AcstInitialState initial;
  initial.void_ratio = 0.8;
  const AcstMaterial material(parameters, initial);
  TriaxialOptions options = rough_mesh(3, 4, 0.05, 10);
  const TriaxialResult serial = run_triaxial(material, options);
  options.distributed = true;
  const TriaxialResult distributed = run_triaxial(material, options);
  expect_same_answer(serial, distributed, 1e-7);
  EXPECT_GT(serial.steps.back().q, 0.5 * kP0) << "the path reached the plastic range";
}

// A material failure at some points of one process only: every process cuts the step together
// (no process waits for another), and the cut path is the serial one.
TEST(DistributedTriaxial, CutsTheStepOnEveryProcessWhenOneFails) {
  const testing::HypoelasticTestMaterial inner(0.01, 60.0);
  const testing::FailingTestMaterial material(inner, 6e-3);
  TriaxialOptions options = rough_mesh(2, 4, 0.02, 2);
  const TriaxialResult serial = run_triaxial(material, options);
  options.distributed = true;
  const TriaxialResult distributed = run_triaxial(material, options);
  expect_same_answer(serial, distributed, 1e-8);
  ASSERT_EQ(serial.steps.size(), distributed.steps.size());
  for (std::size_t i = 0; i < serial.steps.size(); ++i)
    EXPECT_EQ(serial.steps[i].cuts, distributed.steps[i].cuts) << "step " << i;
  EXPECT_GT(serial.steps.back().cuts, 0) << "the threshold made the steps cut";

  // A hopeless failure ends the run on every process with the same message, naming the process.
  const testing::FailingTestMaterial hopeless(inner, 1e-9);
  options.solver.max_cuts = 3;
  const TriaxialResult failed = run_triaxial(hopeless, options);
  EXPECT_FALSE(failed.completed);
  EXPECT_NE(failed.message.find("process "), std::string::npos) << failed.message;
  EXPECT_NE(failed.message.find("3 cuts"), std::string::npos) << failed.message;
  const std::vector<std::string> messages =
      dealii::Utilities::MPI::all_gather(MPI_COMM_WORLD, failed.message);
  for (const std::string& message : messages) EXPECT_EQ(message, messages.front());
}

// The VTU of a distributed run is one file with every cell, and the CSV is written once.
TEST(DistributedTriaxial, WritesOneVtuWithEveryCell) {
  const testing::HypoelasticTestMaterial material(0.01, 60.0);
  TriaxialOptions options = rough_mesh(2, 3, 0.01, 1);
  options.distributed = true;
  const std::string directory =
      ::testing::TempDir() + "sffcal_distributed_" +
      std::to_string(dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, ::getpid(), 0));
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::filesystem::create_directories(directory);
  MPI_Barrier(MPI_COMM_WORLD);
  options.vtu_prefix = directory + "/mesh";
  options.csv_path = directory + "/mesh.csv";
  const TriaxialResult result = run_triaxial(material, options);
  ASSERT_TRUE(result.completed) << result.message;
  MPI_Barrier(MPI_COMM_WORLD);
  for (const char* name : {"/mesh_0000.vtu", "/mesh_0001.vtu", "/mesh.pvd", "/mesh.csv"})
    EXPECT_TRUE(std::filesystem::exists(directory + name)) << name;
  std::ifstream vtu(directory + "/mesh_0001.vtu");
  const std::string text((std::istreambuf_iterator<char>(vtu)), std::istreambuf_iterator<char>());
  std::size_t cells = 0;
  for (std::size_t at = text.find("NumberOfCells=\""); at != std::string::npos;
       at = text.find("NumberOfCells=\"", at + 1))
    cells += std::stoul(text.substr(at + 15));
  EXPECT_EQ(cells, 2u * 2u * 3u) << "every cell once, over the pieces of the file";
  EXPECT_NE(text.find("\"process\""), std::string::npos);
  MPI_Barrier(MPI_COMM_WORLD);
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::filesystem::remove_all(directory);
  MPI_Barrier(MPI_COMM_WORLD);
  // A folder that does not exist: every process refuses by name, none hangs.
  options.vtu_prefix = directory + "/missing/mesh";
  options.csv_path.clear();
  try {
    run_triaxial(material, options);
    ADD_FAILURE() << "a VTU in a missing folder was not refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("missing"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fe_model

// MPI is initialised once for all tests (one thread per process: the processes are the
// parallelism); only process 0 prints gtest's report.
int main(int argc, char** argv) {
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0) {
    ::testing::TestEventListeners& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  return RUN_ALL_TESTS();
}
