/* MuJoCo's own mass properties of each body of an MJCF file, as MuJoCo compiles them (the independent
 * reference of tests/apps/mujoco_reference_test.sh): one JSON line per body with mass, COM and the
 * inertia tensor about it, in the body's frame (MuJoCo keeps principal moments and the rotation of
 * their axes: R diag(I) Rᵀ). Built by the test script against Debian's libmujoco-dev; tumble never links
 * MuJoCo.   mujoco_bodies MODEL.xml */
#include <mujoco/mujoco.h>
#include <stdio.h>

int main(int argc, char** argv) {
  char error[1000] = "";
  if (argc != 2) return 2;
  mjModel* m = mj_loadXML(argv[1], NULL, error, sizeof error);
  if (!m) {
    fprintf(stderr, "mujoco: %s\n", error);
    return 1;
  }
  for (int b = 1; b < m->nbody; ++b) {
    const mjtNum* q = m->body_iquat + 4 * b;
    mjtNum R[9], I[9], RI[9];
    mju_quat2Mat(R, q);
    for (int i = 0; i < 9; ++i) I[i] = 0;
    for (int i = 0; i < 3; ++i) I[4 * i] = m->body_inertia[3 * b + i];
    /* R I Rᵀ */
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        RI[3 * i + j] = 0;
        for (int k = 0; k < 3; ++k) RI[3 * i + j] += R[3 * i + k] * I[3 * k + j];
      }
    /* An unnamed body is "body#ID", as tumble names it (MuJoCo's body id, the world being 0). */
    char unnamed[32];
    const char* name = mj_id2name(m, mjOBJ_BODY, b);
    if (!name) {
      snprintf(unnamed, sizeof unnamed, "body#%d", b);
      name = unnamed;
    }
    printf("{\"name\": \"%s\", \"mass\": %.17g, \"com\": [%.17g, %.17g, %.17g], \"inertia\": [", name,
           m->body_mass[b], m->body_ipos[3 * b], m->body_ipos[3 * b + 1], m->body_ipos[3 * b + 2]);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        mjtNum x = 0;
        for (int k = 0; k < 3; ++k) x += RI[3 * i + k] * R[3 * j + k];
        printf("%.17g%s", x, i == 2 && j == 2 ? "" : ", ");
      }
    printf("]}\n");
  }
  mj_deleteModel(m);
  return 0;
}
