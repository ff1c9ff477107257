/* Small 3-vector and rotation kernels for the convex-shape module (header-only, pure).
 *
 * A unit quaternion q = (w,x,y,z) rotates v to q v q* ; as a matrix (row-major, body -> world)
 *   R = [1-2(y²+z²)  2(xy-wz)    2(xz+wy)
 *        2(xy+wz)    1-2(x²+z²)  2(yz-wx)
 *        2(xz-wy)    2(yz+wx)    1-2(x²+y²)]
 * (Shoemake 1985). The inverse rotation is R^T. Prefix convex_ avoids clashing with the DEM
 * core's own quaternion helpers.
 */
#pragma once
#include <petscsys.h>

static inline PetscReal convex_dot(const PetscReal a[3], const PetscReal b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void convex_cross(const PetscReal a[3], const PetscReal b[3], PetscReal c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

static inline void convex_sub(const PetscReal a[3], const PetscReal b[3], PetscReal c[3])
{
  c[0] = a[0] - b[0];
  c[1] = a[1] - b[1];
  c[2] = a[2] - b[2];
}

static inline PetscReal convex_norm(const PetscReal a[3])
{
  return PetscSqrtReal(convex_dot(a, a));
}

/* Rotation matrix of a quaternion; q need not be exactly unit (it is normalised here). */
static inline void convex_quat_to_matrix(const PetscReal q[4], PetscReal R[9])
{
  const PetscReal s = 1.0 / (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  const PetscReal w = q[0], x = q[1], y = q[2], z = q[3];
  R[0] = 1 - 2 * s * (y * y + z * z);
  R[1] = 2 * s * (x * y - w * z);
  R[2] = 2 * s * (x * z + w * y);
  R[3] = 2 * s * (x * y + w * z);
  R[4] = 1 - 2 * s * (x * x + z * z);
  R[5] = 2 * s * (y * z - w * x);
  R[6] = 2 * s * (x * z - w * y);
  R[7] = 2 * s * (y * z + w * x);
  R[8] = 1 - 2 * s * (x * x + y * y);
}

/* out = R v */
static inline void convex_mat_vec(const PetscReal R[9], const PetscReal v[3], PetscReal out[3])
{
  out[0] = R[0] * v[0] + R[1] * v[1] + R[2] * v[2];
  out[1] = R[3] * v[0] + R[4] * v[1] + R[5] * v[2];
  out[2] = R[6] * v[0] + R[7] * v[1] + R[8] * v[2];
}

/* out = R^T v */
static inline void convex_mat_tvec(const PetscReal R[9], const PetscReal v[3], PetscReal out[3])
{
  out[0] = R[0] * v[0] + R[3] * v[1] + R[6] * v[2];
  out[1] = R[1] * v[0] + R[4] * v[1] + R[7] * v[2];
  out[2] = R[2] * v[0] + R[5] * v[1] + R[8] * v[2];
}

/* Quaternion of a rotation by angle (radians) about a unit axis. */
static inline void convex_quat_from_axis_angle(const PetscReal axis[3], PetscReal angle, PetscReal q[4])
{
  const PetscReal s = PetscSinReal(0.5 * angle);
  q[0]              = PetscCosReal(0.5 * angle);
  q[1]              = s * axis[0];
  q[2]              = s * axis[1];
  q[3]              = s * axis[2];
}

/* c = a b (apply b first, then a). */
static inline void convex_quat_mul(const PetscReal a[4], const PetscReal b[4], PetscReal c[4])
{
  c[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
  c[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
  c[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
  c[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
}
