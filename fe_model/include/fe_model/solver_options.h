// Options and logs of the Newton-Raphson load stepping shared by fe_model's problems. No deal.II
// finite-element headers here, so light translation units can include it.
#ifndef FE_MODEL_SOLVER_OPTIONS_H_
#define FE_MODEL_SOLVER_OPTIONS_H_

#include <string>
#include <vector>

#include "fe_model/material.h"

namespace fe_model {

struct SolverOptions {
  /// Newton converges when ||R|| <= residual_rtol * ||R_0|| (R_0: the residual of the step's first
  /// iterate) or ||R|| <= residual_atol * force_scale, force_scale being the norm of the
  /// internal force vector (so the absolute test is relative to the stress level).
  double residual_rtol = 1e-10;
  double residual_atol = 1e-12;
  int max_newton_iterations = 20;
  /// Step cutting: the load increment is halved on a failed material update or a Newton failure;
  /// the increment is never smaller than 2^-max_cuts of the nominal one, and a step that fails at
  /// that size stops the run.
  int max_cuts = 12;
  /// After a successful cut step the increment is doubled again, up to the nominal one.
  bool regrow_after_cut = true;
  /// Newton's first iterate: the committed displacement plus the last converged increment scaled
  /// to the new load increment (a secant extrapolation along the path), with the new boundary
  /// values. Without it the first iterate moves only the loaded boundary, so in a mesh the cells
  /// next to it take the whole increment at first. The converged answer is the same to the
  /// Newton tolerance; the iterations are fewer on a smooth path.
  bool extrapolate_predictor = true;
  /// Treat kUnreliable material updates like failures (cut the step) instead of accepting them.
  bool cut_on_unreliable = false;
  /// Mean dilatation (B-bar) in the Q1 cells: the volumetric strain is the cell's mean. Q1 with
  /// full integration locks when the plastic flow is (nearly) isochoric or dilatant at a rate
  /// tied to the shear (critical state, rough platens); homogeneous fields are unchanged.
  bool mean_dilatation = true;
  /// The linear solve of each Newton correction. kDirect: UMFPACK (serial; its cost grows
  /// fastest with the mesh). kIterative: GMRES preconditioned by an incomplete LU of the tangent,
  /// to linear_rtol of the residual (an inexact Newton step: at the default 1e-8 the Newton
  /// iterations were those of the direct solve in every case measured, docs/fe.md); where GMRES
  /// does not converge (e.g. a strongly indefinite post-peak tangent) that correction falls back
  /// to UMFPACK. kAutomatic: kIterative from iterative_min_dofs degrees of freedom up, kDirect
  /// below.
  enum class LinearSolver { kAutomatic, kDirect, kIterative };
  LinearSolver linear_solver = LinearSolver::kAutomatic;
  double linear_rtol = 1e-8;
  unsigned int max_linear_iterations = 1000;  ///< GMRES, restarted every 100
  unsigned int iterative_min_dofs = 2000;
  /// Print the Newton log (residual norms and ratios) to std::cout.
  bool verbose = false;
  /// Wall-clock budget of the solid's whole run [s], counted from its construction; 0: none. A
  /// Newton iteration that starts past it ends the run with a message naming the budget (no cut:
  /// a smaller increment does not give the time back). Distributed, the processes decide together.
  double wall_time_limit = 0.0;
};

/// The record of one Newton solve (one attempted load increment).
struct NewtonLog {
  double load_start = 0.0;  ///< load factor of the committed state the attempt starts from
  double load_end = 0.0;    ///< load factor the attempt tries to reach
  bool converged = false;
  int iterations =
      0;  ///< number of linear solves (0 if the first iterate already satisfied the test)
  /// ||R_k|| over the free degrees of freedom, k = 0 .. iterations (one more entry than solves).
  std::vector<double> residual_norms;
  /// ||du_k|| of each Newton correction.
  std::vector<double> update_norms;
  /// GMRES iterations of each correction with the iterative solver (-1: it did not converge and
  /// the direct solver was used); empty with the direct solver.
  std::vector<int> linear_iterations;
  double force_scale = 0.0;
  MaterialStatus worst_status = MaterialStatus::kOk;
  int n_unreliable_points = 0;
  std::string message;  ///< why it did not converge (empty if it did)
  bool out_of_time = false;  ///< stopped by SolverOptions::wall_time_limit

  /// ||R_{k+1}|| / ||R_k||, k = 0 .. iterations-1.
  std::vector<double> residual_ratios() const;
  /// ||R_{k+1}|| / ||R_k||^2 (scaled by force_scale so it is dimensionless): bounded for quadratic
  /// convergence.
  std::vector<double> quadratic_ratios() const;
};

/// The record of reaching one load target, possibly through several cut increments.
struct StepReport {
  bool converged = false;
  double load_reached = 0.0;
  int cuts = 0;                     ///< number of halvings during this step
  std::vector<NewtonLog> attempts;  ///< every Newton solve, failed ones included
  std::string message;
  /// Newton iterations of the converged attempts, summed.
  int total_iterations() const;
};

}  // namespace fe_model

#endif  // FE_MODEL_SOLVER_OPTIONS_H_
