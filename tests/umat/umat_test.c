/* The UMAT entry (model/umat.h) driven as Abaqus/Standard would call it, through umat_ in
 * the shared library sffcal_umat: a drained triaxial path with the lateral stress held by a
 * Newton iteration on DDSDDE, checked against the material-point driver (reference.h) to 1e-8;
 * DDSDDE against centred differences in the UMAT's own conventions; the PROPS and the
 * environment-variable parameter file giving the same answer; NTENS = 4 giving the NTENS = 6
 * answer; and every failure asking for a smaller increment through PNEWDT with a message.
 * Usage: umat_test <parameter file>. Exit status 0 when every check passes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/umat.h"
#include "reference.h"
#include "umat_driver.h"

static const double kP0 = 100e3;    /* initial isotropic stress [Pa] */
static const double kE0 = 0.80;     /* initial void ratio */
static const double kFabric = 0.3;  /* model fabric norm, along the z axis */

static Point make_point(const double* parameters, int ntens, int nprops) {
  Point pt;
  memset(&pt, 0, sizeof pt);
  pt.ntens = ntens;
  pt.nstatv = SFFCAL_UMAT_NSTATV;
  pt.nprops = nprops;
  pt.cmname = "SFFCAL"; /* any name not beginning with CONTACT_NETWORK: the ACST entry */
  for (int i = 0; i < 3; ++i) pt.stress[i] = -kP0; /* tension positive */
  pt.props[SFFCAL_UMAT_PROP_VOID_RATIO] = kE0;
  const double k = kFabric / sqrt(6.0);
  pt.props[SFFCAL_UMAT_PROP_FABRIC + 0] = -k;
  pt.props[SFFCAL_UMAT_PROP_FABRIC + 1] = -k;
  pt.props[SFFCAL_UMAT_PROP_FABRIC + 2] = 2.0 * k;
  for (int i = SFFCAL_UMAT_PROP_PARAMETERS; i < nprops; ++i)
    pt.props[i] = parameters[i - SFFCAL_UMAT_PROP_PARAMETERS];
  return pt;
}

enum { kIncrements = 400 }; /* 5e-4 each: first loading within max_step_error */
static const double kAxialStrainEnd = 0.20;

static void drained_path_matches_driver(const double* parameters) {
  static double q_ref[kIncrements], ev_ref[kIncrements], q[kIncrements], ev[kIncrements];
  static double q_env[kIncrements], ev_env[kIncrements], q4[kIncrements], ev4[kIncrements];
  if (reference_drained_triaxial(parameters, kP0, kE0, kFabric, kAxialStrainEnd, kIncrements,
                                 q_ref, ev_ref) != 0) {
    check(0, "the reference driver path converges", 0.0);
    return;
  }
  Point pt = make_point(parameters, 6, SFFCAL_UMAT_NPROPS_ALL);
  check(umat_drained_triaxial(&pt, kP0, kAxialStrainEnd, kIncrements, q, ev) == 0,
        "drained path through the UMAT (parameters in PROPS) converges", 0.0);
  double q_error = 0.0, ev_error = 0.0, ev_scale = 0.0, q_peak = 0.0;
  for (int n = 0; n < kIncrements; ++n) {
    q_error = fmax(q_error, fabs(q[n] - q_ref[n]) / fabs(q_ref[n]));
    ev_scale = fmax(ev_scale, fabs(ev_ref[n]));
    q_peak = fmax(q_peak, q_ref[n]);
  }
  for (int n = 0; n < kIncrements; ++n) ev_error = fmax(ev_error, fabs(ev[n] - ev_ref[n]));
  ev_error /= ev_scale;
  printf("     (reference: peak q %.1f kPa, final q %.1f kPa, final eps_v %.4f)\n", q_peak / 1e3,
         q_ref[kIncrements - 1] / 1e3, ev_ref[kIncrements - 1]);
  check(q_peak > 1.5 * kP0 && q_error <= 1e-8, "q matches the driver, largest relative error",
        q_error);
  check(ev_error <= 1e-8, "eps_v matches the driver, largest error / max |eps_v|", ev_error);
  /* de = -(1 + e) d eps_v: e = (1 + e0) exp(-eps_v) - 1 along the whole path. */
  const double e_expected = (1.0 + kE0) * exp(-ev[kIncrements - 1]) - 1.0;
  check(pt.statev[SFFCAL_UMAT_STATE_INITIALISED] == 1.0 &&
            fabs(pt.statev[SFFCAL_UMAT_STATE_VOID_RATIO] - e_expected) <= 1e-12,
        "STATEV(2) is the void ratio of the volume change, |error|",
        fabs(pt.statev[SFFCAL_UMAT_STATE_VOID_RATIO] - e_expected));

  /* The parameters from the file named by SFFCAL_ACST_PARAMETERS (NPROPS = 7): same path. */
  Point from_file = make_point(parameters, 6, SFFCAL_UMAT_NPROPS_STATE);
  umat_drained_triaxial(&from_file, kP0, kAxialStrainEnd, kIncrements, q_env, ev_env);
  int same = 1;
  for (int n = 0; n < kIncrements; ++n) same = same && q_env[n] == q[n] && ev_env[n] == ev[n];
  check(same, "the parameter file through SFFCAL_ACST_PARAMETERS gives the same path", 0.0);

  /* NTENS = 4 (plane strain / axisymmetric layout): the same axisymmetric path. */
  Point four = make_point(parameters, 4, SFFCAL_UMAT_NPROPS_ALL);
  umat_drained_triaxial(&four, kP0, kAxialStrainEnd, kIncrements, q4, ev4);
  double four_error = 0.0;
  for (int n = 0; n < kIncrements; ++n) four_error = fmax(four_error, fabs(q4[n] - q[n]) / q[n]);
  check(four_error <= 1e-12, "NTENS = 4 gives the NTENS = 6 path, relative q difference",
        four_error);

  /* PROPS(23..25), n_b_loose, n_G and n_F: at the values NPROPS = 22 stands for, the same path; at
   * others, the driver's path with them. */
  Point all = make_point(parameters, 6, SFFCAL_UMAT_NPROPS_MAX);
  umat_drained_triaxial(&all, kP0, kAxialStrainEnd, kIncrements, q4, ev4);
  same = 1;
  for (int n = 0; n < kIncrements; ++n) same = same && q4[n] == q[n] && ev4[n] == ev[n];
  check(same, "NPROPS = 25 with n_b_loose = 0, n_G = 1/2, n_F = 0 gives the NPROPS = 22 path", 0.0);
  double ours[SFFCAL_UMAT_NPROPS_MAX - SFFCAL_UMAT_PROP_PARAMETERS];
  for (int i = 0; i < SFFCAL_UMAT_NPROPS_MAX - SFFCAL_UMAT_PROP_PARAMETERS; ++i)
    ours[i] = parameters[i];
  ours[15] = 2.0; /* n_b_loose */
  ours[16] = 0.3; /* n_G */
  ours[17] = 3.0; /* n_F */
  if (reference_drained_triaxial(ours, kP0, kE0, kFabric, kAxialStrainEnd, kIncrements, q_ref,
                                 ev_ref) != 0) {
    check(0, "the reference driver path with n_b_loose, n_G and n_F converges", 0.0);
    return;
  }
  Point with_ours = make_point(ours, 6, SFFCAL_UMAT_NPROPS_MAX);
  umat_drained_triaxial(&with_ours, kP0, kAxialStrainEnd, kIncrements, q4, ev4);
  double ours_error = 0.0, moved = 0.0; /* moved: from the path at the defaults */
  for (int n = 0; n < kIncrements; ++n) {
    ours_error = fmax(ours_error, fabs(q4[n] - q_ref[n]) / fabs(q_ref[n]));
    moved = fmax(moved, fabs(q4[n] - q[n]));
  }
  check(ours_error <= 1e-8 && moved > 1e-2 * kP0,
        "n_b_loose, n_G, n_F in PROPS(23..25): the driver's path (and not the defaults'), relative q",
        ours_error);
}

/* DDSDDE against centred differences of STRESS in DSTRAN (engineering shear), at a plastic
 * state after 2 % of axial strain with a general increment. */
static void ddsdde_matches_finite_differences(const double* parameters) {
  Point pt = make_point(parameters, 6, SFFCAL_UMAT_NPROPS_ALL);
  double q[20], ev[20];
  umat_drained_triaxial(&pt, kP0, 0.02, 20, q, ev);
  const double dstran[6] = {2e-4, 1e-4, -6e-4, 1.5e-4, -1e-4, 0.5e-4};
  const double error = ddsdde_difference_error(&pt, dstran, 1e-7);
  check(error <= 1e-6, "DDSDDE matches centred differences, error / max |DDSDDE|", error);
}

static void failures_ask_for_a_smaller_increment(const double* parameters,
                                                 const char* parameter_file) {
  double stress[6], ddsdde[36];
  const double dstran[6] = {0, 0, -1e-4, 0, 0, 0};

  /* A non-physical parameter in PROPS: refused by name, nothing updated. */
  Point bad = make_point(parameters, 6, SFFCAL_UMAT_NPROPS_ALL);
  bad.props[SFFCAL_UMAT_PROP_PARAMETERS + 1] = 0.7; /* nu */
  double pnewdt = call_umat(&bad, dstran, stress, ddsdde, 0);
  check(pnewdt <= 0.5 && message_has("'nu'") && stress[2] == -kP0,
        "nu = 0.7 in PROPS: PNEWDT <= 0.5, message names nu, STRESS unchanged", pnewdt);
  bad.props[SFFCAL_UMAT_PROP_PARAMETERS + 1] = NAN;
  pnewdt = call_umat(&bad, dstran, stress, ddsdde, 0);
  check(pnewdt <= 0.5 && message_has("'nu'"), "nu = NaN in PROPS: refused by name", pnewdt);

  /* An unsupported element layout. */
  Point shell = make_point(parameters, 5, SFFCAL_UMAT_NPROPS_ALL);
  pnewdt = call_umat(&shell, dstran, stress, ddsdde, 0);
  check(pnewdt <= 0.5 && message_has("NSHR"), "NTENS = 5: refused, naming NDI and NSHR", pnewdt);

  /* A parameter file that does not exist, or is out of bounds. */
  setenv("SFFCAL_ACST_PARAMETERS", "/nonexistent/acst.json", 1);
  Point missing = make_point(parameters, 6, SFFCAL_UMAT_NPROPS_STATE);
  pnewdt = call_umat(&missing, dstran, stress, ddsdde, 0);
  check(pnewdt <= 0.5 && message_has("/nonexistent/acst.json"),
        "a missing parameter file: refused, naming the file", pnewdt);
  unsetenv("SFFCAL_ACST_PARAMETERS");
  pnewdt = call_umat(&missing, dstran, stress, ddsdde, 0);
  check(pnewdt <= 0.5 && message_has("SFFCAL_ACST_PARAMETERS"),
        "no parameters at all: the message names SFFCAL_ACST_PARAMETERS", pnewdt);
  setenv("SFFCAL_ACST_PARAMETERS", parameter_file, 1);

  /* An update that cannot be integrated (tension: p leaves the model's domain): PNEWDT asks
   * for a smaller increment, STRESS and STATEV keep the start state, DDSDDE stays finite. */
  Point pt = make_point(parameters, 6, SFFCAL_UMAT_NPROPS_ALL);
  double q[10], ev[10];
  umat_drained_triaxial(&pt, kP0, 0.01, 10, q, ev);
  const Point before = pt;
  const double tension[6] = {0.05, 0.05, 0.05, 0, 0, 0};
  pnewdt = call_umat(&pt, tension, NULL, ddsdde, 1);
  int finite = 1;
  for (int i = 0; i < 36; ++i) finite = finite && isfinite(ddsdde[i]);
  check(pnewdt <= 0.5 && memcmp(pt.stress, before.stress, sizeof pt.stress) == 0 &&
            memcmp(pt.statev, before.statev, sizeof pt.statev) == 0 && finite &&
            strlen(sffcal_umat_last_message()) > 0,
        "a failed update: PNEWDT <= 0.5, STRESS and STATEV unchanged, DDSDDE finite", pnewdt);
  printf("     (message: %s)\n", sffcal_umat_last_message());

  /* An increment too large for one step (3 % of first loading): the update is kept but marked
   * unreliable in STATEV, and PNEWDT asks for a smaller one. */
  Point fresh = make_point(parameters, 6, SFFCAL_UMAT_NPROPS_ALL);
  const double large[6] = {0.01, 0.01, -0.03, 0, 0, 0};
  pnewdt = call_umat(&fresh, large, NULL, ddsdde, 1);
  check(pnewdt <= 0.5 && fresh.statev[SFFCAL_UMAT_STATE_STATUS] == 1.0 &&
            message_has("unreliable"),
        "a 3 % first-loading increment: unreliable in STATEV(21), PNEWDT <= 0.5", pnewdt);

  /* A clean increment clears the message. */
  pnewdt = call_umat(&pt, dstran, stress, ddsdde, 0);
  check(pnewdt == 1.0 && strlen(sffcal_umat_last_message()) == 0,
        "a clean increment: PNEWDT untouched, no message", pnewdt);
}

int main(int argc, char** argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: %s <ACST parameter file>\n", argv[0]);
    return 2;
  }
  double parameters[SFFCAL_UMAT_NPROPS_MAX - SFFCAL_UMAT_PROP_PARAMETERS];
  char message[512];
  if (reference_parameters(argv[1], parameters, message, sizeof message) != 0) {
    fprintf(stderr, "%s\n", message);
    return 2;
  }
  setenv("SFFCAL_ACST_PARAMETERS", argv[1], 1);
  drained_path_matches_driver(parameters);
  ddsdde_matches_finite_differences(parameters);
  failures_ask_for_a_smaller_increment(parameters, argv[1]);
  printf("%d check(s) failed\n", failures);
  return failures == 0 ? 0 : 1;
}
