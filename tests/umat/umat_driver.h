/* What the UMAT C tests share: one integration point called through umat_ as Abaqus/Standard
 * would call it, a drained triaxial path with the lateral stresses held by a Newton iteration on
 * DDSDDE, DDSDDE against centred differences, the last message's text, and the printed checks.
 * C99, header only. */
#ifndef SFFCAL_TESTS_UMAT_DRIVER_H_
#define SFFCAL_TESTS_UMAT_DRIVER_H_

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "model/umat.h"

void umat_(double* stress, double* statev, double* ddsdde, double* sse, double* spd, double* scd,
           double* rpl, double* ddsddt, double* drplde, double* drpldt, const double* stran,
           const double* dstran, const double* time, const double* dtime, const double* temp,
           const double* dtemp, const double* predef, const double* dpred, const char* cmname,
           const int* ndi, const int* nshr, const int* ntens, const int* nstatv,
           const double* props, const int* nprops, const double* coords, const double* drot,
           double* pnewdt, const double* celent, const double* dfgrd0, const double* dfgrd1,
           const int* noel, const int* npt, const int* layer, const int* kspt, const int* kstep,
           const int* kinc, size_t cmname_length);

static int failures = 0;

static void check(int ok, const char* what, double figure) {
  printf("%-4s %-68s %.3e\n", ok ? "ok" : "FAIL", what, figure);
  if (!ok) ++failures;
}

/* Whether the calling thread's last UMAT message contains `text`. */
static int message_has(const char* text) {
  return strstr(sffcal_umat_last_message(), text) != NULL;
}

/* At least the largest NSTATV and NPROPS of either entry (the network one: 29 and 48). */
enum { kMaxStatev = 32, kMaxProps = 48 };

/* One integration point: what Abaqus keeps between increments, and the material's name. */
typedef struct {
  int ntens, nstatv, nprops;
  const char* cmname;
  double stress[6], statev[kMaxStatev], stran[6], props[kMaxProps];
} Point;

/* Calls the UMAT from pt with the strain increment dstran; pt is updated only when commit is set.
 * Returns PNEWDT (1 when the UMAT asked for nothing). */
static double call_umat(Point* pt, const double* dstran, double* stress_out, double* ddsdde,
                        int commit) {
  Point trial = *pt;
  double sse = 0, spd = 0, scd = 0, rpl = 0, ddsddt[6] = {0}, drplde[6] = {0}, drpldt = 0;
  double time[2] = {0, 0}, dtime = 1, temp = 0, dtemp = 0, predef = 0, dpred = 0;
  double coords[3] = {0}, drot[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, celent = 1;
  double dfgrd[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, pnewdt = 1.0;
  int ndi = 3, nshr = trial.ntens - 3, noel = 1, npt = 1;
  int layer = 1, kspt = 1, kstep = 1, kinc = 1;
  umat_(trial.stress, trial.statev, ddsdde, &sse, &spd, &scd, &rpl, ddsddt, drplde, &drpldt,
        trial.stran, dstran, time, &dtime, &temp, &dtemp, &predef, &dpred, trial.cmname, &ndi,
        &nshr, &trial.ntens, &trial.nstatv, trial.props, &trial.nprops, coords, drot, &pnewdt,
        &celent, dfgrd, dfgrd, &noel, &npt, &layer, &kspt, &kstep, &kinc, strlen(trial.cmname));
  if (stress_out) memcpy(stress_out, trial.stress, sizeof trial.stress);
  if (commit) {
    for (int i = 0; i < trial.ntens; ++i) trial.stran[i] += dstran[i];
    *pt = trial;
  }
  return pnewdt;
}

/* Drained triaxial compression through the UMAT: per increment the axial strain is prescribed
 * and the lateral strains found by Newton on DDSDDE until the lateral stresses are -lateral [Pa]
 * to 1e-12 lateral. Fills q [Pa] and eps_v (compression positive) after each increment. Returns
 * 0, or -1 when an increment asked for a smaller step or did not converge. */
static int umat_drained_triaxial(Point* pt, double lateral_stress, double axial_strain_end,
                                 int increments, double* q, double* volumetric_strain) {
  double lateral[2] = {0.0, 0.0};
  for (int n = 0; n < increments; ++n) {
    double dstran[6] = {0}, stress[6], ddsdde[36];
    dstran[2] = -axial_strain_end / increments;
    int converged = 0;
    for (int iteration = 0; iteration < 30 && !converged; ++iteration) {
      dstran[0] = lateral[0];
      dstran[1] = lateral[1];
      if (call_umat(pt, dstran, stress, ddsdde, 0) < 1.0) return -1;
      const double r0 = stress[0] + lateral_stress, r1 = stress[1] + lateral_stress;
      if (fabs(r0) <= 1e-12 * lateral_stress && fabs(r1) <= 1e-12 * lateral_stress) {
        converged = 1;
        break;
      }
      const int m = pt->ntens; /* DDSDDE(I, J) at ddsdde[I + m J] */
      const double a = ddsdde[0], b = ddsdde[m], c = ddsdde[1], d = ddsdde[1 + m];
      const double det = a * d - b * c;
      lateral[0] -= (d * r0 - b * r1) / det;
      lateral[1] -= (a * r1 - c * r0) / det;
    }
    if (!converged) return -1;
    call_umat(pt, dstran, NULL, (double[36]){0}, 1);
    q[n] = -pt->stress[2] + 0.5 * (pt->stress[0] + pt->stress[1]);
    volumetric_strain[n] = -(pt->stran[0] + pt->stran[1] + pt->stran[2]);
  }
  return 0;
}

/* The largest |centred difference of STRESS in DSTRAN (engineering shear, step h) - DDSDDE|
 * over max |DDSDDE|, at pt with the increment dstran (NTENS = 6). */
static double ddsdde_difference_error(const Point* pt, const double* dstran, double h) {
  Point at = *pt;
  double ddsdde[36], stress[6];
  call_umat(&at, dstran, stress, ddsdde, 0);
  double error = 0.0, scale = 0.0;
  for (int j = 0; j < 6; ++j) {
    double plus[6], minus[6], sp[6], sm[6], unused[36];
    memcpy(plus, dstran, sizeof plus);
    memcpy(minus, dstran, sizeof minus);
    plus[j] += h;
    minus[j] -= h;
    call_umat(&at, plus, sp, unused, 0);
    call_umat(&at, minus, sm, unused, 0);
    for (int i = 0; i < 6; ++i) {
      error = fmax(error, fabs((sp[i] - sm[i]) / (2 * h) - ddsdde[i + 6 * j]));
      scale = fmax(scale, fabs(ddsdde[i + 6 * j]));
    }
  }
  return error / scale;
}

#endif
