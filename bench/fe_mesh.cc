// Mesh-level drained triaxial tests with the ACST model (issue 14): the one-eighth specimen on an
// n x n x n mesh of Q1 elements to 30 % axial strain, with smooth platens (the homogeneous test)
// and rough ones (the top face held radially: the specimen bulges at mid-height). Prints a table
// (wall time, steps, Newton iterations, cuts, q/p and eps_v at the end) and writes, in OUT:
// <case>.csv (the curves), <case>_bulge.csv (the radial displacement of the outer face at the
// end) and, with --vtu, <case>_NNNN.vtu + <case>.pvd for ParaView.
//
//   fe_mesh [--cells N] [--steps S] [--strain E] [--threads T] [--vtu] [--only smooth|rough]
//           [--distributed] [--no-extrapolation] [--full-integration]
//           [-o OUT (default out/fe_mesh)] [PARAMS.json]
//   (default: 10 cells per side, 100 steps to 0.3, all threads, examples/acst_toyoura.json;
//    sigma_3 = 100 kPa, e_0 = 0.8, isotropic fabric)
// --distributed: the mesh split over the MPI processes (DistributedSolid), e.g.
//   mpirun -np 2 bench/fe_mesh --distributed --threads 1
// (process 0 prints the table and writes the files). --no-extrapolation: Newton's first iterate
// without the extrapolated increment (SolverOptions::extrapolate_predictor). --full-integration:
// Q1 without B-bar (SolverOptions::mean_dilatation off), the element of CalculiX's C3D8.
#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "model/acst_model.h"
#include "fe_model/acst_material.h"
#include "fe_model/triaxial.h"

namespace {

struct Case {
  std::string name;
  bool rough = false;
};

}  // namespace

int main(int argc, char** argv) {
  std::string parameters_path = std::string(SFFCAL_SOURCE_DIR) + "/examples/acst_toyoura.json";
  std::string output = "out/fe_mesh";  // out/ is ignored by git
  std::string only;
  unsigned int cells = 10, steps = 100, threads = 0;
  double strain = 0.3;
  bool vtu = false, verbose = false, distributed = false, extrapolate = true, bbar = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    try {
      if (a == "--cells") cells = static_cast<unsigned int>(std::stoul(value()));
      else if (a == "--steps") steps = static_cast<unsigned int>(std::stoul(value()));
      else if (a == "--strain") strain = std::stod(value());
      else if (a == "--threads") threads = static_cast<unsigned int>(std::stoul(value()));
      else if (a == "--vtu") vtu = true;
      else if (a == "--verbose") verbose = true;
      else if (a == "--distributed") distributed = true;
      else if (a == "--no-extrapolation") extrapolate = false;
      else if (a == "--full-integration") bbar = false;
      else if (a == "--only") only = value();
      else if (a == "-o") output = value();
      else parameters_path = a;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "fe_mesh: %s: %s\n", a.c_str(), e.what());
      return 2;
    }
  }
  // MPI for --distributed (a program started without mpirun is one process); the thread limit
  // applies to each process.
  dealii::Utilities::MPI::MPI_InitFinalize mpi(
      argc, argv, threads > 0 ? threads : dealii::numbers::invalid_unsigned_int);
  const unsigned int processes = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  const bool prints = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  if (!prints && !std::freopen("/dev/null", "w", stdout)) return 1;
  try {
    const model::acst::Parameters<double> parameters =
        model::acst::read_parameters_json(parameters_path);
    fe_model::AcstInitialState initial;
    initial.void_ratio = 0.8;
    const fe_model::AcstMaterial material(parameters, initial);
    if (prints) std::filesystem::create_directories(output);
    MPI_Barrier(MPI_COMM_WORLD);  // the VTU files are written by every process
    std::printf("fe_mesh: %s, %u^3 Q1 cells%s (%u points), sigma_3 = 100 kPa, e_0 = 0.8, to axial "
                "strain %.2f in %u steps, %u threads%s\n\n",
                parameters_path.c_str(), cells, bbar ? " with B-bar" : " without B-bar",
                8 * cells * cells * cells, strain, steps,
                dealii::MultithreadInfo::n_threads(),
                distributed ? (" per process, distributed over " + std::to_string(processes) +
                               " processes").c_str()
                            : "");
    std::fflush(stdout);
    // q/p two ways: from the platen force as a laboratory measures it (q = F/A - sigma_3, the
    // volume average of sigma_zz being F/A exactly), and from the volume averages of all
    // components (which, with rough platens, include the platens' shear tractions).
    std::printf("| platens | completed | steps | Newton | cuts | wall [s] | q/p platen | "
                "q/p volume average | eps_v end | radial displacement at mid-height [mm] |\n"
                "|---|---|---|---|---|---|---|---|---|---|\n");
    for (const Case& c : {Case{"smooth", false}, Case{"rough", true}}) {
      if (!only.empty() && only != c.name) continue;
      fe_model::TriaxialOptions options;
      options.width = 0.025;  // one eighth of a 50 mm x 50 mm x 100 mm specimen
      options.height = 0.05;
      options.cells_x = options.cells_y = options.cells_z = cells;
      options.confining_pressure = 100e3;
      options.axial_strain_end = strain;
      options.n_steps = steps;
      options.rough_platens = c.rough;
      options.solver.verbose = verbose;
      options.distributed = distributed;
      options.solver.extrapolate_predictor = extrapolate;
      options.solver.mean_dilatation = bbar;
      options.csv_path = output + "/" + c.name + ".csv";
      if (vtu) options.vtu_prefix = output + "/" + c.name;
      const auto t0 = std::chrono::steady_clock::now();
      const fe_model::TriaxialResult r = fe_model::run_triaxial(material, options);
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      int newton = 0, cuts = 0;
      for (const auto& row : r.steps) {
        newton += row.newton_iterations;
        cuts += row.cuts;
      }
      const fe_model::TriaxialStep& end = r.steps.back();
      const double bulge = r.bulge.empty() ? 0.0 : r.bulge.front().radial_displacement;
      const double q_platen = end.axial_stress - options.confining_pressure;
      const double p_platen = options.confining_pressure + q_platen / 3.0;
      std::printf("| %-7s | %-9s | %zu/%u | %6d | %4d | %8.2f | %7.4f | %7.4f | %9.5f | %8.4f |\n",
                  c.name.c_str(), r.completed ? "yes" : "NO", r.steps.size() - 1, steps, newton,
                  cuts, wall, q_platen / p_platen, end.q / end.p, end.volumetric_strain,
                  1e3 * bulge);
      if (!r.completed) std::printf("  %s\n", r.message.c_str());
      std::fflush(stdout);
      if (!prints) continue;
      std::ofstream profile(output + "/" + c.name + "_bulge.csv");
      profile << "# radial displacement u_x of the outer face x = L along y = 0 at the last step; "
                 "z from mid-height [m]\nz,radial_displacement\n";
      for (const fe_model::BulgePoint& b : r.bulge) profile << b.z << ',' << b.radial_displacement << '\n';
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fe_mesh: %s\n", e.what());
    return 1;
  }
  return 0;
}
