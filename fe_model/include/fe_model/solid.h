// A small-strain solid with a Material at every quadrature point: Q1 displacement elements,
// Dirichlet and traction boundary conditions that depend on a load factor, Newton-Raphson with
// the consistent tangent, and load stepping that halves the increment when a step fails.
//
// This is the deal.II core of fe_model (after tutorial step-44's quadrature-point history and
// step-18's small-strain assembly). It is a public header for deal.II programs; light code should
// use fe_model/triaxial.h instead, which hides deal.II.
//
// Conventions: deal.II's, tension positive, throughout this class. Displacements are measured
// from the reference configuration, which carries the initial stress given to the constructor
// (e.g. -p0 I for an isotropically consolidated specimen); that stress must be in equilibrium with
// the tractions at load factor 0, so the first residual of the first step is the load increment
// alone.
//
// Step protocol (MGIS's s0/s1): every quadrature point holds the state at the start of the step
// (committed) and at its end (trial). solve_increment() works on the trial state only; commit()
// makes it the new start state, revert() discards it. advance_to() does both with step cutting.
//
// Two instances of one class template (after tutorial step-40): `Solid`, on one process with
// deal.II's own vectors and matrices (UMFPACK or GMRES + ILU), and `DistributedSolid`, on a
// parallel::distributed::Triangulation (p4est) whose processes each own part of the cells and of
// the degrees of freedom, with Trilinos' distributed vectors and matrix (GMRES + block-Jacobi ILU,
// or Amesos' direct solver). Both run the same cell assembly, Newton iteration and step cutting;
// every process of a DistributedSolid calls every member (they are collective) and gets the same
// global results (norms, volume averages, point displacements).
#ifndef FE_MODEL_SOLID_H_
#define FE_MODEL_SOLID_H_

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/quadrature_point_data.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fe_model/material.h"
#include "fe_model/solver_options.h"

namespace fe_model {

/// Per-quadrature-point history (step-44's PointHistory, with MGIS's two states).
struct PointHistory {
  PointState start;  ///< committed state, at the start of the current load increment
  PointState end;    ///< trial state, at the end of the current increment
  void commit() { start = end; }
  void revert() { end = start; }
};

/// Prescribed displacement on the faces with `boundary_id`, for the components set in
/// `components` (x, y, z). `displacement(x, load)` is evaluated at the support points.
struct DisplacementCondition {
  dealii::types::boundary_id boundary_id = 0;
  std::array<bool, 3> components = {{true, true, true}};
  std::function<dealii::Tensor<1, 3>(const dealii::Point<3>& x, double load)> displacement;
};

/// Traction (force per unit reference area, tension positive: a pressure p is -p n) on the faces
/// with `boundary_id`.
struct TractionCondition {
  dealii::types::boundary_id boundary_id = 0;
  std::function<dealii::Tensor<1, 3>(const dealii::Point<3>& x,
                                     const dealii::Tensor<1, 3>& outward_normal, double load)>
      traction;
};

/// Volume averages over the solid, of the trial (= committed, after commit()) states.
struct VolumeAverages {
  double volume = 0.0;
  SymmetricTensor2 stress;                 ///< tension positive
  SymmetricTensor2 strain;                 ///< tension positive
  std::optional<double> fabric_invariant;  ///< if the material has one
  /// Volume average of each internal variable (empty unless every point has the same number):
  /// meaningful for quantities that average linearly (e.g. the void ratio of a homogeneous body).
  std::vector<double> internal_variables;
};

/// Linear algebra of a Solid on one process.
struct SerialLinearAlgebra {
  using Vector = dealii::Vector<double>;
  using Matrix = dealii::SparseMatrix<double>;
  static constexpr bool kDistributed = false;
};

/// Linear algebra of a Solid distributed over the processes of its triangulation's communicator.
struct DistributedLinearAlgebra {
  using Vector = dealii::TrilinosWrappers::MPI::Vector;
  using Matrix = dealii::TrilinosWrappers::SparseMatrix;
  static constexpr bool kDistributed = true;
};

/// The displacement at one vertex of the mesh.
struct VertexDisplacement {
  dealii::Point<3> position;          ///< [m], reference configuration
  dealii::Tensor<1, 3> displacement;  ///< [m]
};

template <typename LinearAlgebra>
class BasicSolid {
 public:
  using Vector = typename LinearAlgebra::Vector;
  using Matrix = typename LinearAlgebra::Matrix;

  /// `triangulation` and `material` must outlive the Solid. Every quadrature point starts with
  /// material.initial_state(initial_stress). A DistributedSolid needs a
  /// parallel::distributed::Triangulation (its communicator is the Solid's).
  BasicSolid(const dealii::Triangulation<3>& triangulation, const Material& material,
             const SymmetricTensor2& initial_stress, const SolverOptions& options = {});

  void add_displacement_condition(DisplacementCondition condition);
  void add_traction_condition(TractionCondition condition);

  /// Distributes the degrees of freedom, builds the (homogeneous) constraints and the sparsity
  /// pattern and initialises the quadrature-point history. Call after adding the conditions.
  void setup();

  /// Reaches `load_target` from the committed load, cutting the increment in halves on failure
  /// (never below 2^-SolverOptions::max_cuts of the step). Commits every converged increment. On failure the
  /// last converged state stays committed and the report says why; it never throws for a
  /// material or Newton failure.
  StepReport advance_to(double load_target);

  /// One Newton solve from the committed state to `load_end` (trial state only: call commit() or
  /// revert() afterwards).
  NewtonLog solve_increment(double load_end);
  /// Makes the trial state (displacement, quadrature points, load) the committed one.
  void commit();
  /// Discards the trial state.
  void revert();

  /// Evaluates every (locally owned) quadrature point at the trial displacement `u` (from the
  /// committed states) and assembles the residual R = f_int - f_ext(load) over the free degrees
  /// of freedom (zero on constrained ones) and, if `with_matrix`, the tangent dR/du. Returns the
  /// worst material status (over all processes); on kFailed stops at the first failed point and
  /// puts the reason in `message`.
  MaterialStatus assemble(const Vector& u, double load, bool with_matrix,
                          std::string* message = nullptr);

  const dealii::DoFHandler<3>& dof_handler() const { return dof_handler_; }
  const dealii::AffineConstraints<double>& constraints() const { return constraints_; }
  /// Current (trial) displacement (a DistributedSolid's: its locally owned entries).
  const Vector& solution() const { return solution_; }
  const Vector& committed_solution() const { return committed_solution_; }
  const Vector& residual() const { return residual_; }
  const Matrix& tangent_matrix() const { return tangent_matrix_; }
  /// Norm of the unconstrained internal force vector of the last assembly.
  double internal_force_norm() const { return internal_force_norm_; }
  double committed_load() const { return committed_load_; }
  const Material& material() const { return material_; }

  VolumeAverages volume_averages() const;
  /// Calls `visit` with the position and the trial state of every locally owned quadrature point.
  void for_each_point(
      const std::function<void(const dealii::Point<3>&, const PointState&)>& visit) const;
  /// The trial displacement of every vertex for which `select(position)` is true, over the whole
  /// mesh (gathered from every process), in no particular order.
  std::vector<VertexDisplacement> vertex_displacements(
      const std::function<bool(const dealii::Point<3>&)>& select) const;
  /// Writes the displacement (as is) and per-cell averages of p, q, volumetric strain and the
  /// stress components (compression positive, like all of fe_model's output) to a VTU file (one
  /// file, written by all processes together).
  void write_vtu(const std::string& filename) const;

 private:
  void apply_prescribed_displacements(double load, Vector& u) const;
  /// `u` with the ghost entries the locally owned cells read (`u` itself on one process).
  const Vector& with_ghosts(const Vector& u) const;
  /// Whether the Newton corrections use GMRES (SolverOptions::linear_solver).
  bool uses_iterative_solver() const;
  /// Solves tangent x = rhs for a Newton correction (SolverOptions::linear_solver); records the
  /// GMRES iterations in log.
  void solve_linear(const Vector& rhs, Vector& x, NewtonLog& log) const;
  /// Past SolverOptions::wall_time_limit (every process gives the same answer).
  bool out_of_time() const;

  const dealii::Triangulation<3>& triangulation_;
  const Material& material_;
  SymmetricTensor2 initial_stress_;
  SolverOptions options_;

  dealii::FESystem<3> fe_;
  dealii::DoFHandler<3> dof_handler_;
  dealii::QGauss<3> cell_quadrature_;
  dealii::QGauss<2> face_quadrature_;

  std::vector<DisplacementCondition> displacement_conditions_;
  std::vector<TractionCondition> traction_conditions_;

  MPI_Comm communicator_;
  dealii::IndexSet locally_owned_dofs_;
  dealii::IndexSet locally_relevant_dofs_;
  dealii::AffineConstraints<double> constraints_;  // homogeneous: Newton corrections
  dealii::SparsityPattern sparsity_pattern_;       // the serial matrix's
  Matrix tangent_matrix_;
  Vector solution_;
  Vector committed_solution_;
  Vector residual_;
  mutable Vector ghosted_;  // a DistributedSolid's vectors with ghost entries, for reading
  double internal_force_norm_ = 0.0;
  double committed_load_ = 0.0;
  double trial_load_ = 0.0;          // the load_end of the last solve_increment
  Vector last_increment_;            // the last committed displacement increment
  double last_load_increment_ = 0.0;  // and its load increment (0: none yet)
  int last_unreliable_points_ = 0;
  std::chrono::steady_clock::time_point created_ = std::chrono::steady_clock::now();

  dealii::CellDataStorage<typename dealii::Triangulation<3>::cell_iterator, PointHistory> history_;
};

extern template class BasicSolid<SerialLinearAlgebra>;
extern template class BasicSolid<DistributedLinearAlgebra>;

/// A Solid on one process (deal.II's serial vectors and matrix).
using Solid = BasicSolid<SerialLinearAlgebra>;
/// A Solid on a parallel::distributed::Triangulation, over its processes (Trilinos).
using DistributedSolid = BasicSolid<DistributedLinearAlgebra>;

}  // namespace fe_model

#endif  // FE_MODEL_SOLID_H_
