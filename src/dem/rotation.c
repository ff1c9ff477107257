/* Rotation of rigid bodies with a full (principal) inertia tensor: Euler's equations
 *   J dW/dt + W x (J W) = T_b   (body frame, J = diag(J1, J2, J3), W = R^T w, T_b = R^T T)
 * integrated by the symplectic splitting of Dullweber, Leimkuhler & McLachlan (J. Chem. Phys.
 * 107, 5840, 1997), the scheme of NO_SQUISH (Miller et al., J. Chem. Phys. 116, 8649, 2002):
 *   half kick   L <- L + dt/2 T                      (angular momentum, world frame)
 *   free rotor  exact flows of L_k^2 / (2 J_k), in the symmetric order
 *               x dt/2, y dt/2, z dt, y dt/2, x dt/2: the body turns about its own axis k by
 *               phi = tau L_k / J_k while the body-frame L turns by -phi about k
 *   (forces, torques at the new positions and orientations)
 *   half kick   L <- L + dt/2 T.
 * Each rotation is applied to the quaternion and to L as the same exactly orthogonal map, so in
 * free flight the world angular momentum R L_b is conserved to round-off and the energy error
 * stays bounded, O(dt^2) (symplectic). The rotation angle is taken from its Cayley form,
 * half-angle 2 atan(phi/4) instead of phi/2 (no sin/cos; the exact flow of a Hamiltonian
 * differing from L_k^2/2J_k by O(phi^3), which keeps both properties). The spin is stored in
 * the world frame (w = R J^-1 L_b), as the contact kernels use it; q maps body to world.
 * Isotropic bodies (J1 = J2 = J3: cube, regular polyhedra) have w constant in free flight; their
 * free rotor is the single exact rotation by |w| dt about w, q <- (c, s w/|w|) q (Cayley angle). */
#include "dem/dem_core.h"
#include "geom/quat.h"

/* q (c, s e_k): the quaternion product with a rotation about body axis k (sparse form) */
static inline void dem_quat_mul_axis(double *q, int k, double c, double s)
{
  static const int    a[3][4]   = {{1, 0, 3, 2}, {2, 3, 0, 1}, {3, 2, 1, 0}}; /* component of q e_k */
  static const double sgn[3][4] = {{-1, 1, 1, -1}, {-1, -1, 1, 1}, {-1, 1, -1, 1}};
  double              r[4];
  for (int m = 0; m < 4; m++) r[m] = c * q[m] + s * sgn[k][m] * q[a[k][m]];
  for (int m = 0; m < 4; m++) q[m] = r[m];
}

/* One exact rotation of the body about its axis k for time tau: q <- q (c, s e_k), L_b <- R_k^T L_b. */
static inline void dem_rotor_axis(int k, double tau, const double *invJ, double *q, double *L)
{
  const int    a = (k + 1) % 3, b = (k + 2) % 3;
  const double u = 0.25 * tau * L[k] * invJ[k], u2 = u * u, den = 1.0 / (1.0 + u2);
  const double cb = (1.0 - u2) * den, sb = 2.0 * u * den; /* cos, sin of the half angle */
  const double c = cb * cb - sb * sb, s = 2.0 * cb * sb;  /* of the angle */
  dem_quat_mul_axis(q, k, cb, sb);
  const double la = L[a], lb = L[b];
  L[a] = c * la + s * lb;
  L[b] = -s * la + c * lb;
}

/* Rotation matrix of a unit quaternion (row-major, body -> world). */
static inline void dem_quat_matrix(const double *q, double *R)
{
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  R[0] = 1 - 2 * (y * y + z * z), R[1] = 2 * (x * y - w * z), R[2] = 2 * (x * z + w * y);
  R[3] = 2 * (x * y + w * z), R[4] = 1 - 2 * (x * x + z * z), R[5] = 2 * (y * z - w * x);
  R[6] = 2 * (x * z - w * y), R[7] = 2 * (y * z + w * x), R[8] = 1 - 2 * (x * x + y * y);
}

/* Isotropic body: half kick w += hJ T, then rotation by |w| dt about w: q <- (cb, sb w/|w|) q. */
static inline void dem_rotor_iso(double dt, double hJ, const double *T, double *q, double *w)
{
  for (int k = 0; k < 3; k++) w[k] += hJ * T[k];
  const double wn = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  if (wn == 0) return;
  const double u = 0.25 * dt * wn, den = 1.0 / (1.0 + u * u), cb = (1.0 - u * u) * den, sb = 2.0 * u * den / wn;
  const double p[4] = {cb, sb * w[0], sb * w[1], sb * w[2]}, o[4] = {q[0], q[1], q[2], q[3]};
  q[0]           = p[0] * o[0] - p[1] * o[1] - p[2] * o[2] - p[3] * o[3];
  q[1]           = p[0] * o[1] + p[1] * o[0] + p[2] * o[3] - p[3] * o[2];
  q[2]           = p[0] * o[2] - p[1] * o[3] + p[2] * o[0] + p[3] * o[1];
  q[3]           = p[0] * o[3] + p[1] * o[2] - p[2] * o[1] + p[3] * o[0];
  const double s = 1.0 / sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (int k = 0; k < 4; k++) q[k] *= s;
}

/* w <- w + h R J^-1 R^T T (the half kick, in terms of the world spin) */
static inline void dem_kick(const double *R, const double *invJ, double h, const double *T, double *w)
{
  double tb[3], dw[3];
  convex_mat_tvec(R, T, tb);
  for (int k = 0; k < 3; k++) tb[k] *= h * invJ[k];
  convex_mat_vec(R, tb, dw);
  for (int k = 0; k < 3; k++) w[k] += dw[k];
}

/* Writes the local particles' q and w; reads tq and the shapes' inertia. */
PetscErrorCode DemRotateFirstHalf(DemParticles *p, const DemShapeTable *st, double dt)
{
  const double h = 0.5 * dt;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < p->n; i++) {
    const DemShape *sh = &st->shp[p->shape[i]];
    double         *q = p->q + 4 * i, *w = p->w + 3 * i, R[9], wb[3], L[3];
    if (sh->iso) {
      dem_rotor_iso(dt, h * sh->invJ[0], p->tq + 3 * i, q, w);
      continue;
    }
    dem_quat_matrix(q, R);
    dem_kick(R, sh->invJ, h, p->tq + 3 * i, w);
    convex_mat_tvec(R, w, wb);
    for (int k = 0; k < 3; k++) L[k] = sh->J[k] * wb[k];
    const double l2 = L[0] * L[0] + L[1] * L[1] + L[2] * L[2];
    dem_rotor_axis(0, h, sh->invJ, q, L);
    dem_rotor_axis(1, h, sh->invJ, q, L);
    dem_rotor_axis(2, dt, sh->invJ, q, L);
    dem_rotor_axis(1, h, sh->invJ, q, L);
    dem_rotor_axis(0, h, sh->invJ, q, L);
    const double m2 = L[0] * L[0] + L[1] * L[1] + L[2] * L[2]; /* rotations keep |L|: remove */
    if (m2 > 0) {                                              /* the rounding bias of c^2+s^2 */
      const double f = sqrt(l2 / m2);
      for (int k = 0; k < 3; k++) L[k] *= f;
    }
    const double s = 1.0 / sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (int k = 0; k < 4; k++) q[k] *= s;
    dem_quat_matrix(q, R);
    for (int k = 0; k < 3; k++) wb[k] = L[k] * sh->invJ[k];
    convex_mat_vec(R, wb, w);
  }
  PetscCall(PetscLogFlops(250.0 * p->n));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Writes the local particles' w; reads q, tq and the shapes' inertia. */
PetscErrorCode DemRotateSecondHalf(DemParticles *p, const DemShapeTable *st, double dt)
{
  const double h = 0.5 * dt;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < p->n; i++) {
    const DemShape *sh = &st->shp[p->shape[i]];
    double          R[9];
    if (sh->iso) {
      for (int k = 0; k < 3; k++) p->w[3 * i + k] += h * sh->invJ[0] * p->tq[3 * i + k];
      continue;
    }
    dem_quat_matrix(p->q + 4 * i, R);
    dem_kick(R, sh->invJ, h, p->tq + 3 * i, p->w + 3 * i);
  }
  PetscCall(PetscLogFlops(40.0 * p->n));
  PetscFunctionReturn(PETSC_SUCCESS);
}
