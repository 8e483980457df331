// The deal.II core of fe_model: assembly, Newton-Raphson and step cutting (see solid.h).
#include "fe_model/solid.h"

#include <deal.II/base/function.h>
#include <deal.II/base/work_stream.h>
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
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>

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

}  // namespace

Solid::Solid(const dealii::Triangulation<3>& triangulation, const Material& material,
             const SymmetricTensor2& initial_stress, const SolverOptions& options)
    : triangulation_(triangulation),
      material_(material),
      initial_stress_(initial_stress),
      options_(options),
      fe_(dealii::FE_Q<3>(1), 3),
      dof_handler_(triangulation),
      cell_quadrature_(2),
      face_quadrature_(2) {}

void Solid::add_displacement_condition(DisplacementCondition condition) {
  if (!condition.displacement)
    throw std::invalid_argument("DisplacementCondition without a function");
  displacement_conditions_.push_back(std::move(condition));
}

void Solid::add_traction_condition(TractionCondition condition) {
  if (!condition.traction) throw std::invalid_argument("TractionCondition without a function");
  traction_conditions_.push_back(std::move(condition));
}

void Solid::setup() {
  dof_handler_.distribute_dofs(fe_);

  constraints_.clear();
  for (const DisplacementCondition& condition : displacement_conditions_) {
    dealii::VectorTools::interpolate_boundary_values(dof_handler_, condition.boundary_id,
                                                     dealii::Functions::ZeroFunction<3>(3),
                                                     constraints_, to_mask(condition.components));
  }
  constraints_.close();

  dealii::DynamicSparsityPattern dsp(dof_handler_.n_dofs(), dof_handler_.n_dofs());
  dealii::DoFTools::make_sparsity_pattern(dof_handler_, dsp, constraints_, false);
  sparsity_pattern_.copy_from(dsp);
  tangent_matrix_.reinit(sparsity_pattern_);

  solution_.reinit(dof_handler_.n_dofs());
  committed_solution_.reinit(dof_handler_.n_dofs());
  residual_.reinit(dof_handler_.n_dofs());
  committed_load_ = 0.0;

  // step-44: one PointHistory per quadrature point, attached to the cells.
  history_.initialize(triangulation_.begin_active(), triangulation_.end(), cell_quadrature_.size());
  const PointState initial = material_.initial_state(initial_stress_);
  for (const auto& cell : triangulation_.active_cell_iterators()) {
    for (const auto& point : history_.get_data(cell)) {
      point->start = initial;
      point->end = initial;
    }
  }
}

void Solid::apply_prescribed_displacements(double load, dealii::Vector<double>& u) const {
  std::map<dealii::types::global_dof_index, double> values;
  for (const DisplacementCondition& condition : displacement_conditions_) {
    const PrescribedDisplacement function(condition, load);
    dealii::VectorTools::interpolate_boundary_values(dof_handler_, condition.boundary_id, function,
                                                     values, to_mask(condition.components));
  }
  for (const auto& [dof, value] : values) u[dof] = value;
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
// cell in that order is reported), not the other threads.
MaterialStatus Solid::assemble(const dealii::Vector<double>& u, double load, bool with_matrix,
                               std::string* message) {
  const unsigned int dofs_per_cell = fe_.n_dofs_per_cell();
  dealii::Vector<double> internal_force(dof_handler_.n_dofs());
  residual_ = 0.0;
  if (with_matrix) tangent_matrix_ = 0.0;
  MaterialStatus status = MaterialStatus::kOk;
  int unreliable_points = 0;
  bool failed = false;

  auto worker = [&](const typename dealii::DoFHandler<3>::active_cell_iterator& cell,
                    AssemblyScratch& scratch, AssemblyCopy& copy) {
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
    for (unsigned int i = 0; i < dofs_per_cell; ++i)
      internal_force(copy.dof_indices[i]) += copy.cell_internal(i);
    if (with_matrix) {
      constraints_.distribute_local_to_global(copy.cell_matrix, copy.cell_residual,
                                              copy.dof_indices, tangent_matrix_, residual_);
    } else {
      constraints_.distribute_local_to_global(copy.cell_residual, copy.dof_indices, residual_);
    }
  };

  dealii::WorkStream::run(dof_handler_.begin_active(), dof_handler_.end(), worker, copier,
                          AssemblyScratch(fe_, cell_quadrature_, face_quadrature_),
                          AssemblyCopy(dofs_per_cell));
  last_unreliable_points_ = unreliable_points;
  if (failed) return MaterialStatus::kFailed;
  internal_force_norm_ = internal_force.l2_norm();
  if (options_.cut_on_unreliable && status == MaterialStatus::kUnreliable) {
    if (message) *message = std::to_string(unreliable_points) + " unreliable material update(s)";
  }
  return status;
}

NewtonLog Solid::solve_increment(double load_end) {
  NewtonLog log;
  log.load_start = committed_load_;
  log.load_end = load_end;

  // Predictor: the committed displacement with the prescribed values of the new load; Newton
  // corrections then satisfy homogeneous constraints.
  solution_ = committed_solution_;
  apply_prescribed_displacements(load_end, solution_);

  dealii::Vector<double> correction(dof_handler_.n_dofs());
  dealii::Vector<double> minus_residual(dof_handler_.n_dofs());

  for (int k = 0;; ++k) {
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
    if (options_.verbose) {
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

bool Solid::uses_iterative_solver() const {
  using LinearSolver = SolverOptions::LinearSolver;
  return options_.linear_solver == LinearSolver::kIterative ||
         (options_.linear_solver == LinearSolver::kAutomatic &&
          dof_handler_.n_dofs() >= options_.iterative_min_dofs);
}

void Solid::solve_linear(const dealii::Vector<double>& rhs, dealii::Vector<double>& x,
                         NewtonLog& log) const {
  if (uses_iterative_solver()) {
    // GMRES with ILU(0) of the tangent (Saad 2003, §9.3 and §10.3), restarted every 100
    // iterations. Deterministic: serial, no dependence on the thread count.
    dealii::SparseILU<double> ilu;
    ilu.initialize(tangent_matrix_);
    dealii::SolverControl control(options_.max_linear_iterations, options_.linear_rtol * rhs.l2_norm(), false, false);
    // Right preconditioning: the tolerance applies to the true residual of the Newton system.
    dealii::SolverGMRES<dealii::Vector<double>> gmres(
        control, dealii::SolverGMRES<dealii::Vector<double>>::AdditionalData(100, true));
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
  dealii::SparseDirectUMFPACK direct;
  direct.initialize(tangent_matrix_);
  direct.vmult(x, rhs);
}

void Solid::commit() {
  committed_solution_ = solution_;
  for (const auto& cell : triangulation_.active_cell_iterators())
    for (const auto& point : history_.get_data(cell)) point->commit();
}

void Solid::revert() {
  solution_ = committed_solution_;
  for (const auto& cell : triangulation_.active_cell_iterators())
    for (const auto& point : history_.get_data(cell)) point->revert();
}

StepReport Solid::advance_to(double load_target) {
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
      committed_load_ = next;
      if (next == load_target) break;
      if (options_.regrow_after_cut && depth > 0) {
        increment *= 2.0;
        --depth;
      }
      continue;
    }
    revert();
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
    if (options_.verbose) {
      std::cout << "  cut: " << failure << "; retrying with load increment " << increment << '\n';
    }
  }
  report.converged = true;
  report.load_reached = committed_load_;
  return report;
}

VolumeAverages Solid::volume_averages() const {
  dealii::FEValues<3> fe_values(fe_, cell_quadrature_, dealii::update_JxW_values);
  VolumeAverages averages;
  double fabric_sum = 0.0;
  bool has_fabric = true;
  bool same_size = true;
  bool first = true;
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
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

void Solid::for_each_point(
    const std::function<void(const dealii::Point<3>&, const PointState&)>& visit) const {
  dealii::FEValues<3> fe_values(fe_, cell_quadrature_, dealii::update_quadrature_points);
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    fe_values.reinit(cell);
    const auto history = history_.get_data(cell);
    for (unsigned int q = 0; q < cell_quadrature_.size(); ++q) {
      visit(fe_values.quadrature_point(q), history[q]->end);
    }
  }
}

void Solid::write_vtu(const std::string& filename) const {
  const unsigned int n_cells = triangulation_.n_active_cells();
  dealii::Vector<double> p(n_cells), q(n_cells), volumetric_strain(n_cells);
  std::array<dealii::Vector<double>, 6> components;
  for (auto& c : components) c.reinit(n_cells);
  const std::array<std::pair<unsigned int, unsigned int>, 6> index = {
      {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}}};
  const std::array<const char*, 6> names = {
      {"stress_xx", "stress_yy", "stress_zz", "stress_xy", "stress_xz", "stress_yz"}};
  for (const auto& cell : triangulation_.active_cell_iterators()) {
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
    for (unsigned int k = 0; k < 6; ++k)
      components[k](c) = -stress[index[k].first][index[k].second];
  }

  dealii::DataOut<3> data_out;
  data_out.attach_dof_handler(dof_handler_);
  const std::vector<std::string> displacement_names(3, "displacement");
  const std::vector<dealii::DataComponentInterpretation::DataComponentInterpretation>
      interpretation(3, dealii::DataComponentInterpretation::component_is_part_of_vector);
  data_out.add_data_vector(solution_, displacement_names, dealii::DataOut<3>::type_dof_data,
                           interpretation);
  data_out.add_data_vector(p, "p", dealii::DataOut<3>::type_cell_data);
  data_out.add_data_vector(q, "q", dealii::DataOut<3>::type_cell_data);
  data_out.add_data_vector(volumetric_strain, "volumetric_strain",
                           dealii::DataOut<3>::type_cell_data);
  for (unsigned int k = 0; k < 6; ++k) {
    data_out.add_data_vector(components[k], names[k], dealii::DataOut<3>::type_cell_data);
  }
  data_out.build_patches();
  std::ofstream out(filename);
  if (!out) throw std::runtime_error("cannot open " + filename + " for writing");
  data_out.write_vtu(out);
}

}  // namespace fe_model
