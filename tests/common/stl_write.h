/* Writes triangles (9 doubles each) as an ASCII STL file on rank 0 of comm, for the mesh-wall
 * tests (the facet normals written are zeros: the reader takes them from the vertex order). */
#pragma once
#include <stdio.h>
#include <petscsys.h>

static inline PetscErrorCode TestWriteStl(MPI_Comm comm, const char *path, PetscInt ntri, const double *v)
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    FILE *f = fopen(path, "w");
    PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s", path);
    fprintf(f, "solid test\n");
    for (PetscInt t = 0; t < ntri; t++) {
      fprintf(f, "facet normal 0 0 0\nouter loop\n");
      for (int j = 0; j < 3; j++) fprintf(f, "vertex %.17g %.17g %.17g\n", v[9 * t + 3 * j], v[9 * t + 3 * j + 1], v[9 * t + 3 * j + 2]);
      fprintf(f, "endloop\nendfacet\n");
    }
    fprintf(f, "endsolid test\n");
    PetscCheck(fclose(f) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "cannot write %s", path);
  }
  PetscCallMPI(MPI_Barrier(comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A grid of 2 nu nv triangles over the parallelogram o + s e1 + t e2, s in [0, nu], t in [0, nv]
 * (cells of e1 x e2, each split along a diagonal that alternates): v gets 18 nu nv doubles. */
static inline void TestGridTriangles(const double o[3], const double e1[3], const double e2[3], PetscInt nu, PetscInt nv, double *v)
{
  /* corners q = 0..3 of cell (i, j) at (i + (q & 1), j + (q >> 1)); triangles along the diagonal
     0-3 or 1-2 by the cell's parity. Written without a table of corner copies: from that form
     GCC 12.2 -O3 -march=native on an AVX-512 machine made zero-area triangles in
     dem/test_mesh_motion's main (not with -fno-tree-vectorize, nor without -march=native). */
  static const int tri[2][6] = {{0, 1, 3, 0, 3, 2}, {0, 1, 2, 1, 3, 2}};
  PetscInt         t         = 0;
  for (PetscInt i = 0; i < nu; i++)
    for (PetscInt j = 0; j < nv; j++)
      for (int a = 0; a < 6; a++, t++) {
        const int    q = tri[(i + j) % 2][a];
        const double s = (double)(i + (q & 1)), u = (double)(j + (q >> 1));
        for (int k = 0; k < 3; k++) v[3 * t + k] = o[k] + s * e1[k] + u * e2[k];
      }
}

/* The box lo..hi as its sides (lo, then hi, of each axis; without the top z = hi[2] if open_top),
 * each a grid of n x n cells split along alternating diagonals: v gets 18 n^2 doubles (2 n^2
 * triangles) a side. Returns the number of triangles. */
static inline PetscInt TestBoxTriangles(const double lo[3], const double hi[3], PetscInt n, PetscBool open_top, double *v)
{
  PetscInt t = 0;
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) {
      const int a = (d + 1) % 3, b = (d + 2) % 3;
      double    o[3] = {lo[0], lo[1], lo[2]}, e1[3] = {0, 0, 0}, e2[3] = {0, 0, 0};
      if (open_top && d == 2 && s == 1) continue;
      o[d]  = s ? hi[d] : lo[d];
      e1[a] = (hi[a] - lo[a]) / n;
      e2[b] = (hi[b] - lo[b]) / n;
      TestGridTriangles(o, e1, e2, n, n, v + 18 * n * n * t);
      t++;
    }
  return 2 * n * n * t;
}
