// The deal.II core of fe_model: assembly, Newton-Raphson and step cutting (see solid.h).
#include "fe_model/solid.h"

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/work_stream.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/fe_values_extractors.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_ilu.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "sffcal/output_file.h"

namespace fe_model {
namespace {

using dealii::Point;
using dealii::Tensor;

const dealii::FEValuesExtractors::Vector kDisplacement(0);

// A deal.II Function<3> with 3 components evaluating a DisplacementCondition at a fixed load.
class PrescribedDisplacement : public dealii::Function<3> {
 public:
  PrescribedDisplacement(const DisplacementCondition& condition, double load)
      : dealii::Function<3>(3), condition_(condition), load_(load) {}
  double value(const Point<3>& x, const unsigned int component) const override {
    return condition_.displacement(x, load_)[component];
  }
  void vector_value(const Point<3>& x, dealii::Vector<double>& values) const override {
    const Tensor<1, 3> u = condition_.displacement(x, load_);
    for (unsigned int d = 0; d < 3; ++d) values[d] = u[d];
  }

 private:
  const DisplacementCondition& condition_;
  double load_;
};

dealii::ComponentMask to_mask(const std::array<bool, 3>& components) {
  return dealii::ComponentMask(std::vector<bool>(components.begin(), components.end()));
}

bool is_finite(const SymmetricTensor2& t) {
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = i; j < 3; ++j)
      if (!std::isfinite(t[i][j])) return false;
  return true;
}

bool is_finite(const SymmetricTensor4& t) {
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = i; j < 3; ++j)
      for (unsigned int k = 0; k < 3; ++k)
        for (unsigned int l = k; l < 3; ++l)
          if (!std::isfinite(t[i][j][k][l])) return false;
  return true;
}

// Compression-positive mean stress and triaxial deviator (z axial) of a tension-positive stress.
double mean_pressure(const SymmetricTensor2& stress) { return -dealii::trace(stress) / 3.0; }
double triaxial_deviator(const SymmetricTensor2& stress) {
  return -stress[2][2] + 0.5 * (stress[0][0] + stress[1][1]);
}

// This process's rank in a DistributedSolid's communicator, 0 for a Solid (whose program may not
// have initialised MPI, where asking MPI is an error).
template <typename LinearAlgebra>
unsigned int process_rank(MPI_Comm communicator) {
  if constexpr (LinearAlgebra::kDistributed)
    return dealii::Utilities::MPI::this_mpi_process(communicator);
  else
    return 0;
}

MPI_Comm communicator_of(const dealii::Triangulation<3>& triangulation, bool distributed) {
  if (distributed &&
      !dynamic_cast<const dealii::parallel::DistributedTriangulationBase<3>*>(&triangulation))
    throw std::invalid_argument(
        "DistributedSolid needs a parallel::distributed::Triangulation");
  return triangulation.get_communicator();
}

}  // namespace

template <typename LinearAlgebra>
BasicSolid<LinearAlgebra>::BasicSolid(const dealii::Triangulation<3>& triangulation,
                                      const Material& material,
                                      const SymmetricTensor2& initial_stress,
                                      const SolverOptions& options)
    : triangulation_(triangulation),
      material_(material),
      initial_stress_(initial_stress),
      options_(options),
      fe_(dealii::FE_Q<3>(1), 3),
      dof_handler_(triangulation),
      cell_quadrature_(2),
      face_quadrature_(2),
      communicator_(communicator_of(triangulation, LinearAlgebra::kDistributed)) {}

template <typename LinearAlgebra>
void BasicSolid<LinearAlgebra>::add_displacement_condition(DisplacementCondition condition) {
  if (!condition.displacement)
    throw std::invalid_argument("DisplacementCondition without a function");
  displacement_conditions_.push_back(std::move(condition));
}

template <typename LinearAlgebra>
void BasicSolid<LinearAlgebra>::add_traction_condition(TractionCondition condition) {
  if (!condition.traction) throw std::invalid_argument("TractionCondition without a function");
  traction_conditions_.push_back(std::move(condition));
}

template <typename LinearAlgebra>
void BasicSolid<LinearAlgebra>::setup() {
  dof_handler_.distribute_dofs(fe_);
  locally_owned_dofs_ = dof_handler_.locally_owned_dofs();
  dealii::DoFTools::extract_locally_relevant_dofs(dof_handler_, locally_relevant_dofs_);

  constraints_.clear();
  if constexpr (LinearAlgebra::kDistributed) constraints_.reinit(locally_relevant_dofs_);
  for (const DisplacementCondition& condition : displacement_conditions_) {
    dealii::VectorTools::interpolate_boundary_values(dof_handler_, condition.boundary_id,
                                                     dealii::Functions::ZeroFunction<3>(3),
                                                     constraints_, to_mask(condition.components));
  }
  constraints_.close();

  if constexpr (LinearAlgebra::kDistributed) {
    // step-40: each process holds the matrix rows and vector entries of the degrees of freedom it
    // owns; the ghosted vector adds those its cells read.
    dealii::TrilinosWrappers::SparsityPattern pattern(locally_owned_dofs_, locally_owned_dofs_,
                                                      locally_relevant_dofs_, communicator_);
    dealii::DoFTools::make_sparsity_pattern(
        dof_handler_, pattern, constraints_, false,
        process_rank<LinearAlgebra>(communicator_));
    pattern.compress();
    tangent_matrix_.reinit(pattern);
    for (Vector* v : {&solution_, &committed_solution_, &residual_, &last_increment_})
      v->reinit(locally_owned_dofs_, communicator_);
    ghosted_.reinit(locally_owned_dofs_, locally_relevant_dofs_, communicator_);
  } else {
    dealii::DynamicSparsityPattern dsp(dof_handler_.n_dofs(), dof_handler_.n_dofs());
    dealii::DoFTools::make_sparsity_pattern(dof_handler_, dsp, constraints_, false);
    sparsity_pattern_.copy_from(dsp);
    tangent_matrix_.reinit(sparsity_pattern_);
    for (Vector* v : {&solution_, &committed_solution_, &residual_, &last_increment_})
      v->reinit(dof_handler_.n_dofs());
  }
  committed_load_ = trial_load_ = last_load_increment_ = 0.0;

  // step-44: one PointHistory per quadrature point, attached to the (locally owned) cells.
  const PointState initial = material_.initial_state(initial_stress_);
  for (const auto& cell : triangulation_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    history_.initialize(cell, cell_quadrature_.size());
    for (const auto& point : history_.get_data(cell)) {
      point->start = initial;
      point->end = initial;
    }
  }
}

template <typename LinearAlgebra>
void BasicSolid<LinearAlgebra>::apply_prescribed_displacements(double load, Vector& u) const {
  std::map<dealii::types::global_dof_index, double> values;
  for (const DisplacementCondition& condition : displacement_conditions_) {
    const PrescribedDisplacement function(condition, load);
    dealii::VectorTools::interpolate_boundary_values(dof_handler_, condition.boundary_id, function,
                                                     values, to_mask(condition.components));
  }
  for (const auto& [dof, value] : values)
    if (locally_owned_dofs_.is_element(dof)) u[dof] = value;
  u.compress(dealii::VectorOperation::insert);
}

template <typename LinearAlgebra>
const typename LinearAlgebra::Vector& BasicSolid<LinearAlgebra>::with_ghosts(const Vector& u) const {
  if constexpr (LinearAlgebra::kDistributed) {
    ghosted_ = u;
    return ghosted_;
  } else {
    return u;
  }
}

namespace {

// Per-thread scratch of the assembly (WorkStream copies it once per thread).
struct AssemblyScratch {
  AssemblyScratch(const dealii::FiniteElement<3>& fe, const dealii::Quadrature<3>& quadrature,
                  const dealii::Quadrature<2>& face_quadrature)
      : fe_face_values(fe, face_quadrature,
                       dealii::update_values | dealii::update_quadrature_points |
                           dealii::update_normal_vectors | dealii::update_JxW_values),
        strains(quadrature.size()),
        shape_strain(fe.n_dofs_per_cell()),
        mean_divergence(fe.n_dofs_per_cell()) {}
  AssemblyScratch(const AssemblyScratch& other)
      : fe_face_values(other.fe_face_values.get_fe(), other.fe_face_values.get_quadrature(),
                       other.fe_face_values.get_update_flags()),
        strains(other.strains.size()),
        shape_strain(other.shape_strain.size()),
        mean_divergence(other.mean_divergence.size()) {}
  dealii::FEFaceValues<3> fe_face_values;
  std::vector<SymmetricTensor2> strains;
  std::vector<SymmetricTensor2> shape_strain;
  std::vector<double> mean_divergence;  // (1/V_cell) int div N_i dV, for the mean dilatation
};

// What one cell contributes, handed to the (sequential, in-order) copier.
struct AssemblyCopy {
  explicit AssemblyCopy(unsigned int dofs_per_cell)
      : cell_matrix(dofs_per_cell, dofs_per_cell),
        cell_residual(dofs_per_cell),
        cell_internal(dofs_per_cell),
        dof_indices(dofs_per_cell) {}
  dealii::FullMatrix<double> cell_matrix;
  dealii::Vector<double> cell_residual;  // f_int - f_ext of the cell
  dealii::Vector<double> cell_internal;  // f_int of the cell
  std::vector<dealii::types::global_dof_index> dof_indices;
  MaterialStatus status = MaterialStatus::kOk;
  int unreliable_points = 0;
  std::string failure;  // the reason of a failed point (the first in the cell)
};

}  // namespace

// The cells are assembled in parallel with deal.II's WorkStream (TBB threads, after tutorial
// step-9): each cell's material updates write only that cell's quadrature-point history, and the
// copier adds the cell contributions in the cells' order, so the result is the same for any
// number of threads, bit for bit. A failed point stops the assembly's result (the first failed
// cell in that order is reported), not the other threads. A DistributedSolid's processes each
// assemble their own cells; the sums over processes, and the reduction of the statuses, come
// after every process has finished its cells (they are collective).
template <typename LinearAlgebra>
MaterialStatus BasicSolid<LinearAlgebra>::assemble(const Vector& u_owned, double load,
                                                   bool with_matrix, std::string* message) {
  const unsigned int dofs_per_cell = fe_.n_dofs_per_cell();
  const Vector& u = with_ghosts(u_owned);
  Vector internal_force;
  internal_force.reinit(residual_);
  residual_ = 0.0;
  if (with_matrix) tangent_matrix_ = 0.0;
  MaterialStatus status = MaterialStatus::kOk;
  int unreliable_points = 0;
  bool failed = false;

  using CellIterator = typename dealii::DoFHandler<3>::active_cell_iterator;
  auto worker = [&](const CellIterator& cell, AssemblyScratch& scratch, AssemblyCopy& copy) {
    // A fresh FEValues per cell: a reused one skips recomputing the Jacobians when the cell is a
    // translation of the one it saw last (deal.II's CellSimilarity), which changes them in the
    // last bit, and which cell a thread's scratch saw last depends on the scheduling.
    dealii::FEValues<3> fe_values(fe_, cell_quadrature_,
                                  dealii::update_gradients | dealii::update_JxW_values);
    fe_values.reinit(cell);
    cell->get_dof_indices(copy.dof_indices);
    copy.cell_matrix = 0.0;
    copy.cell_residual = 0.0;
    copy.cell_internal = 0.0;
    copy.status = MaterialStatus::kOk;
    copy.unreliable_points = 0;
    copy.failure.clear();
    fe_values[kDisplacement].get_function_symmetric_gradients(u, scratch.strains);
    const std::vector<std::shared_ptr<PointHistory>> history = history_.get_data(cell);
    const unsigned int n_q_points = fe_values.n_quadrature_points;
    const bool bbar = options_.mean_dilatation;
    if (bbar) {
      // Mean dilatation (B-bar; Hughes 1980, de Souza Neto, Peric & Owen 2008 §15.4): every
      // point of the cell takes the cell's mean volumetric strain, its deviatoric strain its own.
      // B-bar is linear in u, so the tangent below stays the exact derivative of the residual.
      double volume = 0.0;
      std::fill(scratch.mean_divergence.begin(), scratch.mean_divergence.end(), 0.0);
      for (unsigned int q = 0; q < n_q_points; ++q) {
        volume += fe_values.JxW(q);
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          scratch.mean_divergence[i] += fe_values[kDisplacement].divergence(i, q) * fe_values.JxW(q);
      }
      double mean_dilatation = 0.0;
      for (unsigned int i = 0; i < dofs_per_cell; ++i) {
        scratch.mean_divergence[i] /= volume;
        mean_dilatation += scratch.mean_divergence[i] * u(copy.dof_indices[i]);
      }
      for (unsigned int q = 0; q < n_q_points; ++q)
        scratch.strains[q] += (mean_dilatation - dealii::trace(scratch.strains[q])) / 3.0 *
                              dealii::unit_symmetric_tensor<3>();
    }

    for (unsigned int q = 0; q < n_q_points; ++q) {
      PointHistory& point = *history[q];
      const SymmetricTensor2 increment = scratch.strains[q] - point.start.strain;
      const MaterialUpdate update = material_.update(point.start, increment, point.end);
      MaterialStatus point_status = update.status;
      std::string reason = update.message;
      if (point_status != MaterialStatus::kFailed &&
          (!is_finite(point.end.stress) || !is_finite(update.tangent))) {
        point_status = MaterialStatus::kFailed;
        reason = "non-finite stress or tangent";
      }
      if (point_status == MaterialStatus::kFailed) {
        std::ostringstream out;
        out << material_.name() << " update failed at cell " << cell->active_cell_index()
            << ", quadrature point " << q << " (|strain increment| = " << increment.norm() << ")"
            << (reason.empty() ? "" : ": " + reason);
        copy.failure = out.str();
        copy.status = MaterialStatus::kFailed;
        return;
      }
      if (point_status == MaterialStatus::kUnreliable) ++copy.unreliable_points;
      copy.status = worst(copy.status, point_status);

      const double JxW = fe_values.JxW(q);
      for (unsigned int i = 0; i < dofs_per_cell; ++i) {
        scratch.shape_strain[i] = fe_values[kDisplacement].symmetric_gradient(i, q);
        if (bbar)
          scratch.shape_strain[i] +=
              (scratch.mean_divergence[i] - fe_values[kDisplacement].divergence(i, q)) / 3.0 *
              dealii::unit_symmetric_tensor<3>();
      }
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        copy.cell_internal(i) += (scratch.shape_strain[i] * point.end.stress) * JxW;
      if (with_matrix) {
        for (unsigned int j = 0; j < dofs_per_cell; ++j) {
          const SymmetricTensor2 stress_j = update.tangent * scratch.shape_strain[j];
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            copy.cell_matrix(i, j) += (scratch.shape_strain[i] * stress_j) * JxW;
        }
      }
    }
    copy.cell_residual = copy.cell_internal;

    // External forces: f_ext = int N t dA on the traction faces (R = f_int - f_ext).
    for (const auto& face : cell->face_iterators()) {
      if (!face->at_boundary()) continue;
      for (const TractionCondition& condition : traction_conditions_) {
        if (face->boundary_id() != condition.boundary_id) continue;
        scratch.fe_face_values.reinit(cell, face);
        for (unsigned int q = 0; q < face_quadrature_.size(); ++q) {
          const Tensor<1, 3> traction =
              condition.traction(scratch.fe_face_values.quadrature_point(q),
                                 scratch.fe_face_values.normal_vector(q), load);
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            copy.cell_residual(i) -= (scratch.fe_face_values[kDisplacement].value(i, q) * traction) *
                                     scratch.fe_face_values.JxW(q);
        }
      }
    }
  };

  auto copier = [&](const AssemblyCopy& copy) {
    if (failed) return;
    if (copy.status == MaterialStatus::kFailed) {
      failed = true;
      if (message) *message = copy.failure;
      return;
    }
    unreliable_points += copy.unreliable_points;
    status = worst(status, copy.status);
    internal_force.add(copy.dof_indices, copy.cell_internal);
    if (with_matrix) {
      constraints_.distribute_local_to_global(copy.cell_matrix, copy.cell_residual,
                                              copy.dof_indices, tangent_matrix_, residual_);
    } else {
      constraints_.distribute_local_to_global(copy.cell_residual, copy.dof_indices, residual_);
    }
  };

  dealii::WorkStream::run(
      dealii::filter_iterators(dof_handler_.active_cell_iterators(),
                               dealii::IteratorFilters::LocallyOwnedCell()),
      worker, copier, AssemblyScratch(fe_, cell_quadrature_, face_quadrature_),
      AssemblyCopy(dofs_per_cell));
  if constexpr (LinearAlgebra::kDistributed) {
    // Every process takes part, the failed ones included, so that none waits for another.
    if (with_matrix) tangent_matrix_.compress(dealii::VectorOperation::add);
    residual_.compress(dealii::VectorOperation::add);
    internal_force.compress(dealii::VectorOperation::add);
    // The messages are gathered only after a failure (every process knows of it by then).
    const bool failed_here = failed;
    failed = dealii::Utilities::MPI::logical_or(failed, communicator_);
    if (failed) {
      const std::vector<std::string> messages = dealii::Utilities::MPI::all_gather(
          communicator_, failed_here && message ? *message : std::string());
      if (message) *message = "";
      for (unsigned int rank = 0; message && rank < messages.size() && message->empty(); ++rank)
        if (!messages[rank].empty())
          *message = "process " + std::to_string(rank) + ": " + messages[rank];
    }
    unreliable_points = dealii::Utilities::MPI::sum(unreliable_points, communicator_);
    status = static_cast<MaterialStatus>(
        dealii::Utilities::MPI::max(static_cast<int>(status), communicator_));
  }
  last_unreliable_points_ = unreliable_points;
  if (failed) return MaterialStatus::kFailed;
  internal_force_norm_ = internal_force.l2_norm();
  if (options_.cut_on_unreliable && status == MaterialStatus::kUnreliable) {
    if (message) *message = std::to_string(unreliable_points) + " unreliable material update(s)";
  }
  return status;
}

template <typename LinearAlgebra>
NewtonLog BasicSolid<LinearAlgebra>::solve_increment(double load_end) {
  NewtonLog log;
  log.load_start = committed_load_;
  log.load_end = load_end;

  // Predictor: the committed displacement, plus (SolverOptions::extrapolate_predictor) the last
  // converged increment scaled to this one's load increment, with the prescribed values of the
  // new load; Newton corrections then satisfy homogeneous constraints.
  trial_load_ = load_end;
  solution_ = committed_solution_;
  if (options_.extrapolate_predictor && last_load_increment_ != 0.0)
    solution_.add((load_end - committed_load_) / last_load_increment_, last_increment_);
  apply_prescribed_displacements(load_end, solution_);

  Vector correction, minus_residual;
  correction.reinit(solution_);
  minus_residual.reinit(solution_);

  for (int k = 0;; ++k) {
    if (out_of_time()) {
      std::ostringstream out;
      out << "the run passed its wall-time limit of " << options_.wall_time_limit
          << " s at Newton iteration " << k << " towards load factor " << load_end;
      log.message = out.str();
      log.out_of_time = true;
      return log;
    }
    std::string message;
    const MaterialStatus status = assemble(solution_, load_end, true, &message);
    log.worst_status = worst(log.worst_status, status);
    log.n_unreliable_points = last_unreliable_points_;
    if (status == MaterialStatus::kFailed ||
        (options_.cut_on_unreliable && status == MaterialStatus::kUnreliable)) {
      log.message = "Newton iteration " + std::to_string(k) + ": " + message;
      return log;
    }
    const double norm = residual_.l2_norm();
    log.residual_norms.push_back(norm);
    log.force_scale = internal_force_norm_;
    if (options_.verbose && process_rank<LinearAlgebra>(communicator_) == 0) {
      std::cout << "    newton " << k << "  |R| = " << std::scientific << std::setprecision(3)
                << norm;
      if (k > 0) {
        const double previous = log.residual_norms[k - 1];
        std::cout << "  |R|/|R_prev| = " << norm / previous << "  |R|/|R_prev|^2*|f_int| = "
                  << norm * log.force_scale / (previous * previous);
      }
      std::cout << std::defaultfloat << '\n';
    }
    if (!std::isfinite(norm)) {
      log.message = "Newton iteration " + std::to_string(k) + ": non-finite residual";
      return log;
    }
    const bool relative_ok = k > 0 && norm <= options_.residual_rtol * log.residual_norms.front();
    const bool absolute_ok = norm <= options_.residual_atol * log.force_scale;
    if (relative_ok || absolute_ok) {
      log.converged = true;
      return log;
    }
    if (k == options_.max_newton_iterations) {
      std::ostringstream out;
      out << "Newton did not converge in " << k << " iterations (|R| = " << norm
          << ", |R_0| = " << log.residual_norms.front() << ")";
      log.message = out.str();
      return log;
    }

    minus_residual = residual_;
    minus_residual *= -1.0;
    solve_linear(minus_residual, correction, log);
    constraints_.distribute(correction);
    solution_ += correction;
    log.update_norms.push_back(correction.l2_norm());
    log.iterations = k + 1;
  }
}

template <typename LinearAlgebra>
bool BasicSolid<LinearAlgebra>::out_of_time() const {
  if (!(options_.wall_time_limit > 0.0)) return false;
  double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - created_).count();
  // One decision for all processes, or one would stop while the others wait in an assembly.
  if constexpr (LinearAlgebra::kDistributed)
    elapsed = dealii::Utilities::MPI::max(elapsed, communicator_);
  return elapsed > options_.wall_time_limit;
}

template <typename LinearAlgebra>
bool BasicSolid<LinearAlgebra>::uses_iterative_solver() const {
  using LinearSolver = SolverOptions::LinearSolver;
  return options_.linear_solver == LinearSolver::kIterative ||
         (options_.linear_solver == LinearSolver::kAutomatic &&
          dof_handler_.n_dofs() >= options_.iterative_min_dofs);
}

template <typename LinearAlgebra>
void BasicSolid<LinearAlgebra>::solve_linear(const Vector& rhs, Vector& x, NewtonLog& log) const {
  if (uses_iterative_solver()) {
    // GMRES with ILU(0) of the tangent (Saad 2003, §9.3 and §10.3), restarted every 100
    // iterations. Deterministic: no dependence on the thread count. Distributed, the ILU is
    // Ifpack's, of each process's diagonal block (block Jacobi), so the GMRES iterations, not the
    // answer to linear_rtol, depend on the number of processes.
    using Preconditioner =
        std::conditional_t<LinearAlgebra::kDistributed, dealii::TrilinosWrappers::PreconditionILU,
                           dealii::SparseILU<double>>;
    Preconditioner ilu;
    ilu.initialize(tangent_matrix_);
    dealii::SolverControl control(options_.max_linear_iterations,
                                  options_.linear_rtol * rhs.l2_norm(), false, false);
    // Right preconditioning: the tolerance applies to the true residual of the Newton system.
    dealii::SolverGMRES<Vector> gmres(control,
                                      typename dealii::SolverGMRES<Vector>::AdditionalData(100, true));
    x = 0.0;
    try {
      gmres.solve(tangent_matrix_, x, rhs, ilu);
      log.linear_iterations.push_back(static_cast<int>(control.last_step()));
      return;
    } catch (const dealii::SolverControl::NoConvergence&) {
      log.linear_iterations.push_back(-1);  // fell back to the direct solver
    } catch (const std::exception&) {       // a zero pivot in the ILU
      log.linear_iterations.push_back(-1);
    }
  }
  if constexpr (LinearAlgebra::kDistributed) {
    // Amesos' KLU on the whole matrix (gathered to one process): for small meshes and fallbacks.
    dealii::SolverControl control;
    dealii::TrilinosWrappers::SolverDirect direct(control);
    direct.solve(tangent_matrix_, x, rhs);
  } else {
    dealii::SparseDirectUMFPACK direct;
    direct.initialize(tangent_matrix_);
    direct.vmult(x, rhs);
  }
}

template <typename LinearAlgebra>
void BasicSolid<LinearAlgebra>::commit() {
  last_increment_ = solution_;
  last_increment_ -= committed_solution_;
  last_load_increment_ = trial_load_ - committed_load_;
  committed_load_ = trial_load_;
  committed_solution_ = solution_;
  for (const auto& cell : triangulation_.active_cell_iterators())
    if (cell->is_locally_owned())
      for (const auto& point : history_.get_data(cell)) point->commit();
}

template <typename LinearAlgebra>
void BasicSolid<LinearAlgebra>::revert() {
  solution_ = committed_solution_;
  for (const auto& cell : triangulation_.active_cell_iterators())
    if (cell->is_locally_owned())
      for (const auto& point : history_.get_data(cell)) point->revert();
}

template <typename LinearAlgebra>
StepReport BasicSolid<LinearAlgebra>::advance_to(double load_target) {
  StepReport report;
  const double nominal = load_target - committed_load_;
  if (nominal == 0.0) {
    report.converged = true;
    report.load_reached = committed_load_;
    return report;
  }
  // depth: how many times the current increment has been halved from the nominal one. It is
  // bounded by max_cuts over the whole step (a success in between regrows the increment but does
  // not reset the bound), so a step whose admissible increment shrinks towards zero stops instead
  // of creeping on.
  double increment = nominal;
  int depth = 0;
  while (true) {
    double next = committed_load_ + increment;
    // Snap to the target when within round-off of it, or when overshooting.
    if ((load_target - next) / nominal <= 1e-12) next = load_target;
    NewtonLog log = solve_increment(next);
    const bool converged = log.converged;
    const std::string failure = log.message;
    report.attempts.push_back(std::move(log));
    if (converged) {
      commit();
      if (next == load_target) break;
      if (options_.regrow_after_cut && depth > 0) {
        increment *= 2.0;
        --depth;
      }
      continue;
    }
    revert();
    if (report.attempts.back().out_of_time) {
      report.message = failure;
      report.load_reached = committed_load_;
      return report;
    }
    if (depth == options_.max_cuts) {
      std::ostringstream out;
      out << "load step to load factor " << load_target << " failed at load factor "
          << committed_load_ << " after " << options_.max_cuts << " cuts (smallest increment "
          << increment << "): " << failure;
      report.message = out.str();
      report.load_reached = committed_load_;
      return report;
    }
    ++depth;
    ++report.cuts;
    increment *= 0.5;
    if (options_.verbose && process_rank<LinearAlgebra>(communicator_) == 0) {
      std::cout << "  cut: " << failure << "; retrying with load increment " << increment << '\n';
    }
  }
  report.converged = true;
  report.load_reached = committed_load_;
  return report;
}

template <typename LinearAlgebra>
VolumeAverages BasicSolid<LinearAlgebra>::volume_averages() const {
  dealii::FEValues<3> fe_values(fe_, cell_quadrature_, dealii::update_JxW_values);
  VolumeAverages averages;
  double fabric_sum = 0.0;
  bool has_fabric = true;
  bool same_size = true;
  bool first = true;
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fe_values.reinit(cell);
    const auto history = history_.get_data(cell);
    for (unsigned int q = 0; q < cell_quadrature_.size(); ++q) {
      const PointState& state = history[q]->end;
      const double JxW = fe_values.JxW(q);
      averages.volume += JxW;
      averages.stress += JxW * state.stress;
      averages.strain += JxW * state.strain;
      if (first) {
        averages.internal_variables.assign(state.internal_variables.size(), 0.0);
        first = false;
      }
      if (same_size && state.internal_variables.size() == averages.internal_variables.size()) {
        for (std::size_t k = 0; k < state.internal_variables.size(); ++k)
          averages.internal_variables[k] += JxW * state.internal_variables[k];
      } else {
        same_size = false;
      }
      const std::optional<double> fabric = material_.fabric_invariant(state);
      if (fabric) {
        fabric_sum += JxW * *fabric;
      } else {
        has_fabric = false;
      }
    }
  }
  if constexpr (LinearAlgebra::kDistributed) {
    // The sums over the processes (a process may own no cell: it agrees with any size).
    const MPI_Comm comm = communicator_;
    const std::size_t size = dealii::Utilities::MPI::max(
        first ? std::size_t{0} : averages.internal_variables.size(), comm);
    // (deal.II 9.4 has a logical_or but no logical_and: the minimum of 0/1.)
    same_size = dealii::Utilities::MPI::min(
                    int(same_size && (first || averages.internal_variables.size() == size)),
                    comm) == 1;
    has_fabric = dealii::Utilities::MPI::min(int(has_fabric), comm) == 1;
    averages.internal_variables.resize(same_size ? size : 0, 0.0);
    std::vector<double> sums = averages.internal_variables;
    dealii::Utilities::MPI::sum(averages.internal_variables, comm, sums);
    averages.internal_variables = sums;
    averages.volume = dealii::Utilities::MPI::sum(averages.volume, comm);
    averages.stress = dealii::Utilities::MPI::sum(averages.stress, comm);
    averages.strain = dealii::Utilities::MPI::sum(averages.strain, comm);
    fabric_sum = dealii::Utilities::MPI::sum(fabric_sum, comm);
  }
  averages.stress /= averages.volume;
  averages.strain /= averages.volume;
  if (has_fabric) averages.fabric_invariant = fabric_sum / averages.volume;
  if (same_size) {
    for (double& v : averages.internal_variables) v /= averages.volume;
  } else {
    averages.internal_variables.clear();
  }
  return averages;
}

template <typename LinearAlgebra>
void BasicSolid<LinearAlgebra>::for_each_point(
    const std::function<void(const dealii::Point<3>&, const PointState&)>& visit) const {
  dealii::FEValues<3> fe_values(fe_, cell_quadrature_, dealii::update_quadrature_points);
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fe_values.reinit(cell);
    const auto history = history_.get_data(cell);
    for (unsigned int q = 0; q < cell_quadrature_.size(); ++q) {
      visit(fe_values.quadrature_point(q), history[q]->end);
    }
  }
}

template <typename LinearAlgebra>
std::vector<VertexDisplacement> BasicSolid<LinearAlgebra>::vertex_displacements(
    const std::function<bool(const dealii::Point<3>&)>& select) const {
  const Vector& u = with_ghosts(solution_);
  // Flat (x, y, z, u_x, u_y, u_z) per vertex, each vertex from the process owning its dofs.
  std::vector<double> local;
  std::vector<bool> seen(triangulation_.n_vertices(), false);
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    for (const unsigned int v : cell->vertex_indices()) {
      if (seen[cell->vertex_index(v)]) continue;
      seen[cell->vertex_index(v)] = true;
      if (!select(cell->vertex(v)) || !locally_owned_dofs_.is_element(cell->vertex_dof_index(v, 0)))
        continue;
      for (unsigned int d = 0; d < 3; ++d) local.push_back(cell->vertex(v)[d]);
      for (unsigned int d = 0; d < 3; ++d) local.push_back(u(cell->vertex_dof_index(v, d)));
    }
  }
  std::vector<double> all = local;
  if constexpr (LinearAlgebra::kDistributed) {
    all.clear();
    for (const std::vector<double>& part : dealii::Utilities::MPI::all_gather(communicator_, local))
      all.insert(all.end(), part.begin(), part.end());
  }
  std::vector<VertexDisplacement> vertices(all.size() / 6);
  for (std::size_t k = 0; k < vertices.size(); ++k)
    for (unsigned int d = 0; d < 3; ++d) {
      vertices[k].position[d] = all[6 * k + d];
      vertices[k].displacement[d] = all[6 * k + 3 + d];
    }
  return vertices;
}

template <typename LinearAlgebra>
void BasicSolid<LinearAlgebra>::write_vtu(const std::string& filename) const {
  const unsigned int n_cells = triangulation_.n_active_cells();
  dealii::Vector<double> p(n_cells), q(n_cells), volumetric_strain(n_cells), process(n_cells);
  std::array<dealii::Vector<double>, 6> components;
  for (auto& c : components) c.reinit(n_cells);
  const std::array<std::pair<unsigned int, unsigned int>, 6> index = {
      {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}}};
  const std::array<const char*, 6> names = {
      {"stress_xx", "stress_yy", "stress_zz", "stress_xy", "stress_xz", "stress_yz"}};
  for (const auto& cell : triangulation_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    const auto history = history_.get_data(cell);
    SymmetricTensor2 stress, strain;
    for (const auto& point : history) {
      stress += point->end.stress;
      strain += point->end.strain;
    }
    stress /= static_cast<double>(history.size());
    strain /= static_cast<double>(history.size());
    const unsigned int c = cell->active_cell_index();
    p(c) = mean_pressure(stress);
    q(c) = triaxial_deviator(stress);
    volumetric_strain(c) = -dealii::trace(strain);
    process(c) = process_rank<LinearAlgebra>(communicator_);
    for (unsigned int k = 0; k < 6; ++k)
      components[k](c) = -stress[index[k].first][index[k].second];
  }

  dealii::DataOut<3> data_out;
  data_out.attach_dof_handler(dof_handler_);
  const std::vector<std::string> displacement_names(3, "displacement");
  const std::vector<dealii::DataComponentInterpretation::DataComponentInterpretation>
      interpretation(3, dealii::DataComponentInterpretation::component_is_part_of_vector);
  data_out.add_data_vector(with_ghosts(solution_), displacement_names,
                           dealii::DataOut<3>::type_dof_data, interpretation);
  data_out.add_data_vector(p, "p", dealii::DataOut<3>::type_cell_data);
  data_out.add_data_vector(q, "q", dealii::DataOut<3>::type_cell_data);
  data_out.add_data_vector(volumetric_strain, "volumetric_strain",
                           dealii::DataOut<3>::type_cell_data);
  for (unsigned int k = 0; k < 6; ++k) {
    data_out.add_data_vector(components[k], names[k], dealii::DataOut<3>::type_cell_data);
  }
  if constexpr (LinearAlgebra::kDistributed) {
    data_out.add_data_vector(process, "process", dealii::DataOut<3>::type_cell_data);
    data_out.build_patches();  // of the locally owned cells
    // Every process sees the same folder, so all refuse together (MPI-IO's own error would not
    // name the file).
    const std::filesystem::path folder = std::filesystem::path(filename).parent_path();
    if (!folder.empty() && !std::filesystem::is_directory(folder))
      throw std::runtime_error("cannot open " + filename + " for writing: no folder " +
                               folder.string());
    data_out.write_vtu_in_parallel(filename, communicator_);
  } else {
    data_out.build_patches();
    sffcal::OutputFile file(filename);
    data_out.write_vtu(file.stream());
    file.commit();
  }
}

template class BasicSolid<SerialLinearAlgebra>;
template class BasicSolid<DistributedLinearAlgebra>;

}  // namespace fe_model
