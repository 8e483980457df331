/* STRESS, STATEV and DDSDDE of umat_ along a fixed 60-increment strain path (loading with shear,
 * then unloading), for the ACST and the contact-network entries, printed in %.17g: what
 * same_outputs.sh compares between two builds. Build: cc umat_path_dump.c -lsffcal_umat. */
#include <stdio.h>
#include <string.h>
#include <stddef.h>
void umat_(double*, double*, double*, double*, double*, double*, double*, double*, double*,
           double*, const double*, const double*, const double*, const double*, const double*,
           const double*, const double*, const double*, const char*, const int*, const int*,
           const int*, const int*, const double*, const int*, const double*, const double*,
           double*, const double*, const double*, const double*, const int*, const int*,
           const int*, const int*, const int*, const int*, size_t);
static void run(const char* name, const double* props, int nprops, int nstatv) {
  double stress[6] = {-1e5, -1e5, -1e5, 0, 0, 0}, statev[64] = {0}, ddsdde[36], z[64] = {0};
  double stran[6] = {0}, pnewdt = 1.0, drot[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  int ndi = 3, nshr = 3, ntens = 6, noel = 1, npt = 1, one = 1;
  for (int inc = 0; inc < 60; ++inc) {
    double d[6] = {1e-4, 1e-4, -5e-4, 4e-5, -2e-5, 1e-5};
    if (inc > 40) for (int k = 0; k < 6; ++k) d[k] = -0.5 * d[k];
    pnewdt = 1.0;
    umat_(stress, statev, ddsdde, z, z, z, z, z, z, z, stran, d, z, z, z, z, z, z, name, &ndi,
          &nshr, &ntens, &nstatv, props, &nprops, z, drot, &pnewdt, z, drot, drot, &noel, &npt,
          &one, &one, &one, &inc, strlen(name));
    printf("%s %d pnewdt %.17g\n", name, inc, pnewdt);
    for (int k = 0; k < 6; ++k) printf("%.17g ", stress[k]);
    printf("\n");
    for (int k = 0; k < nstatv; ++k) printf("%.17g ", statev[k]);
    printf("\n");
    for (int k = 0; k < 36; ++k) printf("%.17g ", ddsdde[k]);
    printf("\n");
  }
}
int main(void) {
  /* ACST: e0, F0, then the Toyoura-like parameters of examples/acst_toyoura.json (and ours) */
  double acst[25] = {0.8, -0.05, -0.05, 0.1, 0.02, 0, 0,
                     125, 0.05, 1.25, 0.712, 0.934, 0.019, 0.7, 0.01, 7.05, 0.968, 1.1, 0.704,
                     3.5, 0.1, 5.0, 2.0, 0.4, 5.0};
  run("SFFCAL", acst, 25, 22);
  double net[48] = {0.62, 5.5, -0.04, -0.04, 0.08, 0.01, 0, 0, -0.05, -0.05, 0.1, 0, 0.01, 0,
                    -0.01, -0.01, 0.02, 0, 0, 0.005, 150e6};
  double par[27] = {300, 4.6, 0.2, 20, 5, 0.6, 0.3, 30, 0.7, 0.4, 40, 0.1, 0.05, 50, 2, 1, 1,
                    0.5, 0.8, 0.5, 0.7, 2, 0.8, 0.05, 1, 0.5, 0.5};
  memcpy(net + 21, par, sizeof par);
  run("CONTACT_NETWORK", net, 48, 29);
  return 0;
}
