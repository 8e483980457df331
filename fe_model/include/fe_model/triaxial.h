// Element-level drained triaxial compression test on a box specimen (one eighth of it, by
// symmetry), with any fe_model::Material at the quadrature points. This header hides deal.II's
// finite-element classes; fe_model/solid.h is the deal.II-level API underneath.
//
// Geometry and boundary conditions (z is the axial direction):
//   domain [0, L] x [0, L] x [0, H], n_x x n_y x n_z Q1 hexahedra;
//   x = 0, y = 0, z = 0: symmetry, zero normal displacement (tangential free);
//   x = L, y = L:        confining pressure p0, a traction -p0 n (constant);
//   z = H:               prescribed axial displacement u_z = -eps_a H, eps_a growing linearly
//                        with the load factor; tangential free (a smooth platen), or held
//                        (u_x = u_y = 0: a rough platen, TriaxialOptions::rough_platens; with the
//                        symmetry plane z = 0 both platens of the specimen are rough and it bulges
//                        at mid-height).
// Initial state: isotropically consolidated, stress -p0 I (deal.II sign) at zero displacement,
// in equilibrium with the confining traction.
//
// Output convention: COMPRESSION POSITIVE (soil mechanics), whereas deal.II and Material work
// tension positive: axial_strain = -<eps_zz>, volumetric_strain = -<tr eps>,
// p = -<tr sigma>/3, q = sigma_a - sigma_r = -<sigma_zz> + (<sigma_xx> + <sigma_yy>)/2, where <.>
// is the volume average over the specimen.
#ifndef FE_MODEL_TRIAXIAL_H_
#define FE_MODEL_TRIAXIAL_H_

#include <optional>
#include <string>
#include <vector>

#include "fe_model/material.h"
#include "fe_model/solver_options.h"

namespace fe_model {

struct TriaxialOptions {
  double width = 1.0;   ///< L [m], the modelled domain's side in x and y (half the specimen's)
  double height = 2.0;  ///< H [m], the modelled domain's height (half the specimen's)
  unsigned int cells_x = 1;
  unsigned int cells_y = 1;
  unsigned int cells_z = 1;
  double confining_pressure = 100e3;  ///< p0 [Pa], compression positive, held constant
  double axial_strain_end = 0.01;     ///< final axial strain, compression positive
  unsigned int n_steps = 10;          ///< equal axial strain increments
  bool rough_platens = false;  ///< the top face held radially (see above); smooth otherwise
  /// Distribute the mesh over the processes of MPI_COMM_WORLD (a p4est
  /// parallel::distributed::Triangulation with Trilinos linear algebra: DistributedSolid). MPI must
  /// be initialised (e.g. dealii::Utilities::MPI::MPI_InitFinalize in main) and every process
  /// calls run_triaxial with the same options; each gets the whole result, the files are written
  /// once (the CSV and PVD by process 0, each VTU by all together).
  bool distributed = false;
  SolverOptions solver;
  std::string csv_path;    ///< if not empty: one CSV row per converged step (and the initial state)
  /// If not empty: <prefix>_<step, 4 digits>.vtu per converged step and <prefix>.pvd, the
  /// ParaView collection of them with time = axial strain.
  std::string vtu_prefix;
};

/// One converged load step, compression positive.
struct TriaxialStep {
  unsigned int step = 0;  ///< 0: the initial (consolidated) state
  double axial_strain = 0.0;
  double volumetric_strain = 0.0;
  double p = 0.0;              ///< mean effective stress [Pa]
  double q = 0.0;              ///< deviator sigma_a - sigma_r [Pa]
  double axial_stress = 0.0;   ///< <sigma_zz>, compression positive [Pa]
  double radial_stress = 0.0;  ///< (<sigma_xx> + <sigma_yy>)/2, compression positive [Pa]
  std::optional<double> fabric_invariant;  ///< volume average of Material::fabric_invariant
  /// Volume averages of the material's internal variables (VolumeAverages::internal_variables).
  std::vector<double> internal_variables;
  int newton_iterations = 0;               ///< of the converged attempts of this step, summed
  int cuts = 0;                            ///< increment halvings during this step
  MaterialStatus worst_status = MaterialStatus::kOk;  ///< over the converged attempts
  /// Residual norms of the last converged Newton solve of the step.
  std::vector<double> residual_norms;
};

/// The radial displacement of the outer face along its edge x = L, y = 0 (u_x, outward
/// positive) at the last converged step: the bulging profile.
struct BulgePoint {
  double z = 0.0;                    ///< [m], 0 at mid-height of the specimen
  double radial_displacement = 0.0;  ///< [m]
};

struct TriaxialResult {
  bool completed = false;           ///< all steps converged
  std::string message;              ///< why not (empty if completed)
  std::vector<TriaxialStep> steps;  ///< converged steps only (never NaN), the initial state first
  std::vector<StepReport> reports;  ///< one per attempted step, with every Newton log
  std::vector<BulgePoint> bulge;    ///< ascending z
};

/// Runs the test. Throws std::invalid_argument for bad options and std::runtime_error if an output
/// file cannot be written; material and Newton failures end the run with completed == false.
TriaxialResult run_triaxial(const Material& material, const TriaxialOptions& options);

/// Writes the CSV (header + rows) of `steps`, compression positive, SI units.
void write_triaxial_csv(const std::string& path, const std::vector<TriaxialStep>& steps);

}  // namespace fe_model

#endif  // FE_MODEL_TRIAXIAL_H_
