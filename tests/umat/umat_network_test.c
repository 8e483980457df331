/* The contact-network UMAT entry (model/umat_network.h) driven as Abaqus/Standard would call
 * it, through umat_ in the shared library sffcal_umat with a material named CONTACT_NETWORK-...:
 * a drained triaxial path with the lateral stress held by a Newton iteration on DDSDDE against the
 * fit's drained prediction (network_reference.h); the initial mean stress and the void ratio in
 * STATEV; DDSDDE against centred differences in the UMAT's conventions; PROPS and the
 * environment-variable parameter file giving the same answer; NTENS = 4 giving the NTENS = 6
 * answer; the material's name choosing the entry; and every failure asking for a smaller increment
 * through PNEWDT with a message naming the problem.
 * Usage: umat_network_test <contact-network parameter file>. Exit status 0 when all checks pass. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/umat.h"
#include "model/umat_network.h"
#include "network_reference.h"
#include "umat_driver.h"

/* A dense specimen's network at 100 kPa (the first snapshot of bench/reference/dense_100kPa). */
static const double kP0 = 100e3; /* initial isotropic stress [Pa] */
static const double kE0 = 0.574, kZ0 = 6.69;
static const double kAc = -0.022, kAn = 0.040, kAt = -0.0015; /* triaxial parts t(.) */
/* PROPS(22..48) */
enum { kNumParameters = SFFCAL_UMAT_NETWORK_NPROPS_MAX - SFFCAL_UMAT_NETWORK_PROP_PARAMETERS };

/* x diag(-1, -1, 2) / 3 in the order 11, 22, 33, 12, 13, 23. */
static void axisymmetric(double x, double* props) {
  props[0] = props[1] = -x / 3.0;
  props[2] = 2.0 * x / 3.0;
  props[3] = props[4] = props[5] = 0.0;
}

/* youngs_and_parameters: E then the 27 parameters (PROPS 21..48). */
static Point make_point(const double* youngs_and_parameters, int ntens, int nprops) {
  Point pt;
  memset(&pt, 0, sizeof pt);
  pt.ntens = ntens;
  pt.nstatv = SFFCAL_UMAT_NETWORK_NSTATV;
  pt.nprops = nprops;
  pt.cmname = "CONTACT_NETWORK-DENSE";
  for (int i = 0; i < 3; ++i) pt.stress[i] = -kP0; /* tension positive */
  pt.props[SFFCAL_UMAT_NETWORK_PROP_VOID_RATIO] = kE0;
  pt.props[SFFCAL_UMAT_NETWORK_PROP_COORDINATION] = kZ0;
  axisymmetric(kAc, pt.props + SFFCAL_UMAT_NETWORK_PROP_FABRIC);
  axisymmetric(kAn, pt.props + SFFCAL_UMAT_NETWORK_PROP_NORMAL);
  axisymmetric(kAt, pt.props + SFFCAL_UMAT_NETWORK_PROP_TANGENTIAL);
  for (int i = SFFCAL_UMAT_NETWORK_PROP_YOUNGS_MODULUS; i < nprops; ++i)
    pt.props[i] = youngs_and_parameters[i - SFFCAL_UMAT_NETWORK_PROP_YOUNGS_MODULUS];
  return pt;
}

/* STRESS after one increment dstran from the initial state, with NPROPS = nprops and, where
 * index >= 0, PROPS(index + 1) = value. */
static void one_step(const double* youngs_and_parameters, int nprops, int index, double value,
                     const double* dstran, double* stress) {
  Point pt = make_point(youngs_and_parameters, 6, nprops);
  if (index >= 0) pt.props[index] = value;
  double ddsdde[36];
  call_umat(&pt, dstran, stress, ddsdde, 0);
}

/* PROPS(index + 1), a parameter added after the first version: NPROPS = index (without it) gives
 * the same increment dstran as the value `absent`, and `value` a different S33. */
static void added_parameter_acts(const double* youngs_and_parameters, int index, double absent,
                                 double value, const double* dstran, const char* what) {
  double without[6], as_absent[6], other[6];
  one_step(youngs_and_parameters, index, -1, 0.0, dstran, without);
  one_step(youngs_and_parameters, index + 1, index, absent, dstran, as_absent);
  one_step(youngs_and_parameters, index + 1, index, value, dstran, other);
  check(memcmp(without, as_absent, sizeof without) == 0 && fabs(other[2] - without[2]) > 1e-6 * kP0,
        what, fabs(other[2] - without[2]));
}

enum { kIncrements = 400 };
static const double kAxialStrainEnd = 0.20;

static int same_path(const double* q1, const double* ev1, const double* q2, const double* ev2) {
  for (int n = 0; n < kIncrements; ++n)
    if (q1[n] != q2[n] || ev1[n] != ev2[n]) return 0;
  return 1;
}

static void drained_path_matches_driver(const double* youngs_and_parameters) {
  static double q_ref[kIncrements], ev_ref[kIncrements], q[kIncrements], ev[kIncrements];
  static double q2[kIncrements], ev2[kIncrements];
  char message[512];
  if (network_reference_drained_triaxial(youngs_and_parameters, kP0, kE0, kZ0, kAc, kAn, kAt,
                                         kAxialStrainEnd, kIncrements, q_ref, ev_ref, message,
                                         sizeof message) != 0) {
    printf("     (reference: %s)\n", message);
    check(0, "the reference driver path is complete", 0.0);
    return;
  }
  Point pt = make_point(youngs_and_parameters, 6, SFFCAL_UMAT_NETWORK_NPROPS_MAX);
  /* A zero increment first: Lambda is set so that the SFF stress has the mean stress p0. */
  double stress[6], ddsdde[36];
  const double zero[6] = {0};
  call_umat(&pt, zero, stress, ddsdde, 0);
  const double p_start = -(stress[0] + stress[1] + stress[2]) / 3.0;
  check(fabs(p_start / kP0 - 1.0) <= 1e-12,
        "the first increment's SFF stress has the initial mean stress, relative error",
        fabs(p_start / kP0 - 1.0));

  check(umat_drained_triaxial(&pt, kP0, kAxialStrainEnd, kIncrements, q, ev) == 0,
        "drained path through the UMAT (E and parameters in PROPS) converges", 0.0);
  double q_error = 0.0, ev_error = 0.0, ev_scale = 0.0, q_peak = 0.0;
  for (int n = 0; n < kIncrements; ++n) {
    q_error = fmax(q_error, fabs(q[n] - q_ref[n]) / fabs(q_ref[n]));
    ev_error = fmax(ev_error, fabs(ev[n] - ev_ref[n]));
    ev_scale = fmax(ev_scale, fabs(ev_ref[n]));
    q_peak = fmax(q_peak, q_ref[n]);
  }
  ev_error /= ev_scale;
  printf("     (reference: peak q %.1f kPa, final q %.1f kPa, final eps_v %.4f)\n", q_peak / 1e3,
         q_ref[kIncrements - 1] / 1e3, ev_ref[kIncrements - 1]);
  /* The two integrate the same laws with RK4 but may choose different substep counts. */
  check(q_peak > 1.0 * kP0 && q_error <= 1e-7, "q matches the driver, largest relative error",
        q_error);
  check(ev_error <= 1e-7, "eps_v matches the driver, largest error / max |eps_v|", ev_error);
  /* Eq. N1, de = -(1 + e) d eps_v: e = (1 + e0) exp(-eps_v) - 1 along the whole path. */
  const double e_expected = (1.0 + kE0) * exp(-ev[kIncrements - 1]) - 1.0;
  const double e_error = fabs(pt.statev[SFFCAL_UMAT_NETWORK_STATE_VOID_RATIO] - e_expected);
  check(pt.statev[SFFCAL_UMAT_NETWORK_STATE_INITIALISED] == 1.0 && e_error <= 1e-12,
        "STATEV(2) is the void ratio of the volume change, |error|", e_error);
  printf("     (final state: Z %.3f, Lambda %.3e, t(A) %.4f, substeps of the last update %.0f)\n",
         pt.statev[SFFCAL_UMAT_NETWORK_STATE_COORDINATION],
         pt.statev[SFFCAL_UMAT_NETWORK_STATE_LAMBDA],
         pt.statev[SFFCAL_UMAT_NETWORK_STATE_FABRIC + 2] -
             0.5 * (pt.statev[SFFCAL_UMAT_NETWORK_STATE_FABRIC] +
                    pt.statev[SFFCAL_UMAT_NETWORK_STATE_FABRIC + 1]),
         pt.statev[SFFCAL_UMAT_NETWORK_STATE_SUBSTEPS]);

  /* E and the parameters from the file named by SFFCAL_NETWORK_PARAMETERS (NPROPS = 20). */
  Point from_file = make_point(youngs_and_parameters, 6, SFFCAL_UMAT_NETWORK_NPROPS_STATE);
  umat_drained_triaxial(&from_file, kP0, kAxialStrainEnd, kIncrements, q2, ev2);
  check(same_path(q, ev, q2, ev2),
        "the parameter file through SFFCAL_NETWORK_PARAMETERS gives the same path", 0.0);

  /* NTENS = 4 (plane strain / axisymmetric layout): the same axisymmetric path. */
  Point four = make_point(youngs_and_parameters, 4, SFFCAL_UMAT_NETWORK_NPROPS_MAX);
  umat_drained_triaxial(&four, kP0, kAxialStrainEnd, kIncrements, q2, ev2);
  double four_error = 0.0;
  for (int n = 0; n < kIncrements; ++n) four_error = fmax(four_error, fabs(q2[n] - q[n]) / q[n]);
  check(four_error <= 1e-12, "NTENS = 4 gives the NTENS = 6 path, relative q difference",
        four_error);

  /* The parameters added after the first version: without them in PROPS they take their value of
   * the model before them; another value changes an increment that sees them. PROPS(40), c_t: an
   * extension increment; PROPS(41), c_l: a compression increment (Lambda grows, and Z with it);
   * PROPS(42), n_kappa: the same (Lambda grows at another rate). */
  const int ct = SFFCAL_UMAT_NETWORK_PROP_PARAMETERS + 18, cl = ct + 1, nk = ct + 2;
  const double extension[6] = {1e-3, 1e-3, 2e-3, 0, 0, 0}; /* tension positive: the axis unloads */
  const double compression[6] = {0, 0, -2e-3, 0, 0, 0};
  added_parameter_acts(youngs_and_parameters, ct, 1.0, 0.6, extension,
                       "NPROPS = 39 is c_t = 1; c_t = 0.6 in PROPS(40) changes an extension step, "
                       "|dS33| [Pa]");
  added_parameter_acts(youngs_and_parameters, cl, 0.0, 0.1, compression,
                       "NPROPS = 40 is c_l = 0; c_l = 0.1 in PROPS(41) changes a compression step, "
                       "|dS33| [Pa]");
  added_parameter_acts(youngs_and_parameters, nk, 1.0, 0.3, compression,
                       "NPROPS = 41 is n_kappa = 1; n_kappa = 0.3 in PROPS(42) changes a compression "
                       "step, |dS33| [Pa]");
  /* PROPS(43..45), the critical void ratio line (Eq. N7b): d_psi in a compression step (it shears
   * the network), then, with d_psi given, e_gamma and lambda_e. */
  const int dpsi = ct + 3, egamma = ct + 4, lambdae = ct + 5;
  added_parameter_acts(youngs_and_parameters, dpsi, 0.0, 2.0, compression,
                       "NPROPS = 42 is d_psi = 0; d_psi = 2 in PROPS(43) changes a compression step, "
                       "|dS33| [Pa]");
  double with_line[1 + kNumParameters];
  memcpy(with_line, youngs_and_parameters, sizeof with_line);
  with_line[dpsi - SFFCAL_UMAT_NETWORK_PROP_YOUNGS_MODULUS] = 2.0;
  added_parameter_acts(with_line, egamma, 0.8, 0.6, compression,
                       "NPROPS = 43 is e_gamma = 0.8; e_gamma = 0.6 in PROPS(44) changes a "
                       "compression step, |dS33| [Pa]");
  added_parameter_acts(with_line, lambdae, 0.0, 0.05, compression,
                       "NPROPS = 44 is lambda_e = 0; lambda_e = 0.05 in PROPS(45) changes a "
                       "compression step, |dS33| [Pa]");
  /* PROPS(46), w_psi (Eq. N2c): the anisotropies' targets in a compression step. */
  added_parameter_acts(youngs_and_parameters, ct + 6, 0.0, 1.0, compression,
                       "NPROPS = 45 is w_psi = 0; w_psi = 1 in PROPS(46) changes a compression "
                       "step, |dS33| [Pa]");
  /* PROPS(47), r_i (Eq. N2d): the initial fabric, all inherent, kept in a compression step. */
  added_parameter_acts(youngs_and_parameters, ct + 7, 1.0, 0.0, compression,
                       "NPROPS = 46 is r_i = 1; r_i = 0 in PROPS(47) changes a compression step, "
                       "|dS33| [Pa]");
  /* PROPS(48), n_ra (Eq. N3b): the dense network's fabric (xi > 0) at another rate. */
  added_parameter_acts(youngs_and_parameters, ct + 8, 0.0, 3.0, compression,
                       "NPROPS = 47 is n_ra = 0; n_ra = 3 in PROPS(48) changes a compression "
                       "step, |dS33| [Pa]");

  /* The name chooses the entry in any case; another name goes to ACST, which refuses these
   * PROPS (its parameters, PROPS(8..22), would be the anisotropies and E here). */
  Point lower = make_point(youngs_and_parameters, 6, SFFCAL_UMAT_NETWORK_NPROPS_MAX);
  lower.cmname = "contact_network_dense";
  umat_drained_triaxial(&lower, kP0, kAxialStrainEnd, kIncrements, q2, ev2);
  check(same_path(q, ev, q2, ev2), "a lower-case contact_network name: the same path", 0.0);
  Point acst = make_point(youngs_and_parameters, 6, SFFCAL_UMAT_NETWORK_NPROPS_MAX);
  acst.cmname = "SAND";
  const double dstran[6] = {0, 0, -1e-4, 0, 0, 0};
  const double pnewdt = call_umat(&acst, dstran, stress, ddsdde, 0);
  check(pnewdt <= 0.5 && message_has("ACST"),
        "another name goes to the ACST entry (which refuses these PROPS)", pnewdt);
  printf("     (message: %s)\n", sffcal_umat_last_message());
}

/* DDSDDE against centred differences of STRESS in DSTRAN (engineering shear), after 2 % of axial
 * strain with a general increment. */
static void ddsdde_matches_finite_differences(const double* youngs_and_parameters) {
  Point pt = make_point(youngs_and_parameters, 6, SFFCAL_UMAT_NETWORK_NPROPS_MAX);
  double q[20], ev[20];
  umat_drained_triaxial(&pt, kP0, 0.02, 20, q, ev);
  const double dstran[6] = {2e-4, 1e-4, -6e-4, 1.5e-4, -1e-4, 0.5e-4};
  const double error = ddsdde_difference_error(&pt, dstran, 1e-7);
  check(error <= 1e-6, "DDSDDE matches centred differences, error / max |DDSDDE|", error);
}

/* Calls the UMAT once with a small compression on a copy of pt; returns PNEWDT and checks that
 * STRESS came back unchanged. */
static double refused(const Point* pt, int* stress_unchanged) {
  Point trial = *pt;
  double stress[6], ddsdde[36];
  const double dstran[6] = {0, 0, -1e-4, 0, 0, 0};
  const double pnewdt = call_umat(&trial, dstran, stress, ddsdde, 0);
  *stress_unchanged = memcmp(stress, pt->stress, sizeof stress) == 0;
  return pnewdt;
}

static void failures_ask_for_a_smaller_increment(const double* youngs_and_parameters,
                                                 const char* parameter_file) {
  const Point good = make_point(youngs_and_parameters, 6, SFFCAL_UMAT_NETWORK_NPROPS_MAX);
  int unchanged = 0;

  Point bad = good; /* k_a (PROPS(29)) below its bound */
  bad.props[SFFCAL_UMAT_NETWORK_PROP_PARAMETERS + 7] = -1.0;
  double pnewdt = refused(&bad, &unchanged);
  check(pnewdt <= 0.5 && unchanged && message_has("k_a"),
        "k_a = -1 in PROPS: PNEWDT <= 0.5, the message names k_a, STRESS unchanged", pnewdt);

  bad = good;
  bad.props[SFFCAL_UMAT_NETWORK_PROP_YOUNGS_MODULUS] = 0.0;
  pnewdt = refused(&bad, &unchanged);
  check(pnewdt <= 0.5 && unchanged && message_has("PROPS(21)"), "E = 0: refused, naming PROPS(21)",
        pnewdt);

  bad = good; /* A_0 with a trace */
  bad.props[SFFCAL_UMAT_NETWORK_PROP_FABRIC] += 0.01;
  pnewdt = refused(&bad, &unchanged);
  check(pnewdt <= 0.5 && unchanged && message_has("PROPS(3..8)") && message_has("deviatoric"),
        "a non-deviatoric A_0: refused, naming PROPS(3..8)", pnewdt);

  bad = good;
  bad.props[SFFCAL_UMAT_NETWORK_PROP_COORDINATION] = NAN;
  pnewdt = refused(&bad, &unchanged);
  check(pnewdt <= 0.5 && unchanged && message_has("PROPS(2)"), "Z_0 = NaN: refused, naming PROPS(2)",
        pnewdt);

  bad = good;
  bad.nprops = 25;
  pnewdt = refused(&bad, &unchanged);
  check(pnewdt <= 0.5 && message_has("NPROPS = 25"), "NPROPS = 25: refused, saying what to give",
        pnewdt);

  bad = good; /* a tensile initial stress */
  for (int i = 0; i < 3; ++i) bad.stress[i] = kP0;
  pnewdt = refused(&bad, &unchanged);
  check(pnewdt <= 0.5 && unchanged && message_has("compressive"),
        "a tensile initial STRESS: refused, the message says it must be compressive", pnewdt);

  bad = good;
  bad.nstatv = 10;
  pnewdt = refused(&bad, &unchanged);
  check(pnewdt <= 0.5 && message_has("NSTATV"), "NSTATV = 10: refused, naming NSTATV", pnewdt);

  setenv("SFFCAL_NETWORK_PARAMETERS", "/nonexistent/network.json", 1);
  Point missing = make_point(youngs_and_parameters, 6, SFFCAL_UMAT_NETWORK_NPROPS_STATE);
  pnewdt = refused(&missing, &unchanged);
  check(pnewdt <= 0.5 && message_has("/nonexistent/network.json"),
        "a missing parameter file: refused, naming the file", pnewdt);
  unsetenv("SFFCAL_NETWORK_PARAMETERS");
  pnewdt = refused(&missing, &unchanged);
  check(pnewdt <= 0.5 && message_has("SFFCAL_NETWORK_PARAMETERS"),
        "no parameters at all: the message names SFFCAL_NETWORK_PARAMETERS", pnewdt);
  setenv("SFFCAL_NETWORK_PARAMETERS", parameter_file, 1);

  /* Increments that cannot be integrated: STRESS and STATEV keep the start state, DDSDDE finite. */
  Point pt = good;
  double q[10], ev[10], ddsdde[36];
  umat_drained_triaxial(&pt, kP0, 0.01, 10, q, ev);
  const Point before = pt;
  const double not_finite[6] = {0, 0, NAN, 0, 0, 0};
  const double huge[6] = {0, 0, -100.0, 0, 0, 0};
  const double* increments[2] = {not_finite, huge};
  const char* what[2] = {"a NaN increment: PNEWDT <= 0.5, STRESS and STATEV unchanged, message",
                         "a 10,000 % increment: PNEWDT <= 0.5, STRESS and STATEV unchanged"};
  const char* said[2] = {"not finite", "substeps"};
  for (int k = 0; k < 2; ++k) {
    pnewdt = call_umat(&pt, increments[k], NULL, ddsdde, 1);
    int finite = 1;
    for (int i = 0; i < 36; ++i) finite = finite && isfinite(ddsdde[i]);
    check(pnewdt <= 0.5 && memcmp(pt.stress, before.stress, sizeof pt.stress) == 0 &&
              memcmp(pt.statev, before.statev, sizeof pt.statev) == 0 && finite &&
              message_has(said[k]),
          what[k], pnewdt);
    printf("     (message: %s)\n", sffcal_umat_last_message());
    pt = before;
  }

  /* A clean increment clears the message. */
  int ignored = 0;
  pnewdt = refused(&pt, &ignored);
  check(pnewdt == 1.0 && strlen(sffcal_umat_last_message()) == 0,
        "a clean increment: PNEWDT untouched, no message", pnewdt);
}

int main(int argc, char** argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: %s <contact-network parameter file>\n", argv[0]);
    return 2;
  }
  double youngs_and_parameters[1 + kNumParameters];
  char message[512];
  if (network_reference_parameters(argv[1], youngs_and_parameters, message, sizeof message) != 0) {
    fprintf(stderr, "%s\n", message);
    return 2;
  }
  setenv("SFFCAL_NETWORK_PARAMETERS", argv[1], 1);
  drained_path_matches_driver(youngs_and_parameters);
  ddsdde_matches_finite_differences(youngs_and_parameters);
  failures_ask_for_a_smaller_increment(youngs_and_parameters, argv[1]);
  printf("%d check(s) failed\n", failures);
  return failures == 0 ? 0 : 1;
}
