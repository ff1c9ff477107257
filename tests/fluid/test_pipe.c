/* ranks: 1 2 */
/* Hagen-Poiseuille flow in a circular pipe given to the fluid as a vessel (FluidSetVessel, FAVOR
 * with the wall at its distance along each grid line, src/fluid/vessel.c): radius R = 0.5 m,
 * rho = 1 kg/m^3, mu = 1 Pa s, driven by the imposed mean pressure gradient |G| = 0.025 Pa/m
 * along the axis; the steady flow rate is Q = pi R^4 |G| / (8 mu) (u_max = 1.6 mm/s, Re 0.0016).
 *   (a) axis along z, periodic in z (4 cells), box walls in x and y two cells beyond the pipe;
 *   (b) axis tilted by 30 degrees from z in the x-z plane, periodic in x and z with
 *       Lx/Lz = tan 30 deg, so that the periodic images are parallel pipes Lz/2 = 1.25 D apart.
 * Q is the mean over the z-planes of sum a_f u_z hx hy (each plane cuts one pipe, also in (b)).
 * Steady state by implicit viscous steps of dt = 100 h (backward Euler, a decay of at least 1/70
 * per step of the slowest mode; 6 steps). Checks: Q within 1% at 16 cells across the diameter,
 * both orientations; the observed order over 8, 16, 32 cells (tilted: 8, 12, 16); continuity
 * per cell to the Poisson tolerance; u exactly 0 at every closed face (the flux through it is
 * a_f u = 0). Then, on the z-pipe at 8 cells: the explicit viscous term at the stability edge
 * (its adaptive step counts the wall links' stiffness; R = 3.83 h puts a wall 0.024 h from a face)
 * keeps the implicit steady flow; slip walls keep a plug flow exactly;
 * an inlet/outlet pipe carries U_n x the open inlet area through every plane to round-off with 0
 * on the closed inlet faces, and that area is the circle's within 0.5%, and its frame holds the
 * open-volume fractions as the cell field vessel; a run redistributed mid-way gives the same flow. Last, a box with a
 * vessel that cuts nothing (phi = 1) is the box bit for bit. About 4 s on 1 rank. */
#include "fluid_common.h"
#include <hdf5.h>
#include <unistd.h>

typedef struct {
  PetscReal R, s, c, per; /* radius; axis (s, 0, c); spacing of the images along eta (0: none) */
} Pipe;

static PetscReal PipeLevel(const PetscReal x[3], void *ctx)
{
  const Pipe *p   = (const Pipe *)ctx;
  PetscReal   eta = p->c * x[0] - p->s * x[2]; /* offset from the axis through 0 in the x-z plane */
  if (p->per > 0) eta -= p->per * PetscFloorReal(eta / p->per + 0.5);
  return p->R - PetscSqrtReal(eta * eta + x[1] * x[1]);
}

static PetscErrorCode SetOpt(const char *name, const char *value)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsSetValue(NULL, name, value));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode SetOptReal3(const char *name, PetscReal a, PetscReal b, PetscReal c)
{
  char buf[96];
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(buf, sizeof buf, "%.17g,%.17g,%.17g", (double)a, (double)b, (double)c));
  PetscCall(SetOpt(name, buf));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode SetOptInt(const char *name, PetscInt n)
{
  char buf[32];
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(buf, sizeof buf, "%d", (int)n));
  PetscCall(SetOpt(name, buf));
  PetscFunctionReturn(PETSC_SUCCESS);
}

typedef struct {
  PetscReal Q, div, uclosed, rnorm;
  PetscReal qmin, qmax; /* flux through the z-planes of faces (all of them, boundary planes too) */
  PetscReal umin, umax; /* u_z over the open z-faces */
  PetscReal ain;        /* open area of the lowest z-plane (m^2) */
  PetscReal outdiff;    /* frame's /fluid/vessel against the open-volume fractions */
  PetscReal wall;       /* run time (s) */
  PetscInt  its, nclosed;
} PipeResult;

/* Mean flux through the z-planes, the largest |u| on a closed face and their count, the extremes
 * of the plane fluxes and of u_z on open faces. */
static PetscErrorCode PipeMeasure(Fluid fl, PipeResult *r)
{
  DM                    cda, fda;
  Vec                   u, vol, area;
  const PetscScalar ****ua, ****aa;
  PetscInt              xs[3], xm[3], N[3], np;
  PetscReal             loc[3] = {0, 0, 0}, glob[3], ext[2] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL}, gext[2], *q, *gq, hx[3], ain = 0;
  DMBoundaryType        bz;

  PetscFunctionBeginUser;
  PetscCall(FluidGetDMs(fl, &cda, &fda));
  PetscCall(FluidGetVelocity(fl, &u));
  PetscCall(FluidGetOpenFractions(fl, &vol, &area));
  PetscCheck(area, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "the pipe does not cut the grid");
  PetscCall(DMDAGetInfo(cda, NULL, &N[0], &N[1], &N[2], NULL, NULL, NULL, NULL, NULL, NULL, NULL, &bz, NULL));
  { /* the cell sizes from the options the run was made with */
    PetscReal lo[3], hi[3];
    PetscInt  n = 3;
    PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-domain_lo", lo, &n, NULL));
    n = 3;
    PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-domain_hi", hi, &n, NULL));
    for (int d = 0; d < 3; d++) hx[d] = (hi[d] - lo[d]) / N[d];
  }
  np = N[2] + 1;
  PetscCall(PetscCalloc2(np, &q, np, &gq));
  PetscCall(DMDAGetCorners(fda, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(DMDAVecGetArrayDOFRead(fda, u, &ua));
  PetscCall(DMDAVecGetArrayDOFRead(fda, area, &aa));
  for (PetscInt k = xs[2]; k < xs[2] + xm[2]; k++)
    for (PetscInt j = xs[1]; j < xs[1] + xm[1]; j++)
      for (PetscInt i = xs[0]; i < xs[0] + xm[0]; i++) {
        const PetscInt idx[3] = {i, j, k};
        for (int d = 0; d < 3; d++) {
          PetscBool extra = PETSC_FALSE;
          for (int e = 0; e < 3; e++)
            if (e != d && idx[e] == N[e]) extra = PETSC_TRUE; /* unused point (bounded axes) */
          if (extra) continue;
          if (aa[k][j][i][d] == 0) {
            loc[1] = PetscMax(loc[1], PetscAbsScalar(ua[k][j][i][d]));
            loc[2] += 1;
          } else if (d == 2) {
            ext[0] = PetscMax(ext[0], PetscRealPart(ua[k][j][i][d]));
            ext[1] = PetscMax(ext[1], -PetscRealPart(ua[k][j][i][d]));
          }
          if (d == 2) q[k] += PetscRealPart(aa[k][j][i][d] * ua[k][j][i][d]) * hx[0] * hx[1];
          if (d == 2 && k < N[2]) loc[0] += PetscRealPart(aa[k][j][i][d] * ua[k][j][i][d]);
          if (d == 2 && k == 0) ain += PetscRealPart(aa[k][j][i][d]) * hx[0] * hx[1];
        }
      }
  PetscCall(DMDAVecRestoreArrayDOFRead(fda, area, &aa));
  PetscCall(DMDAVecRestoreArrayDOFRead(fda, u, &ua));
  PetscCallMPI(MPI_Allreduce(&loc[0], &glob[0], 1, MPIU_REAL, MPI_SUM, PETSC_COMM_WORLD));
  PetscCallMPI(MPI_Allreduce(&loc[1], &glob[1], 1, MPIU_REAL, MPI_MAX, PETSC_COMM_WORLD));
  PetscCallMPI(MPI_Allreduce(&loc[2], &glob[2], 1, MPIU_REAL, MPI_SUM, PETSC_COMM_WORLD));
  PetscCallMPI(MPI_Allreduce(ext, gext, 2, MPIU_REAL, MPI_MAX, PETSC_COMM_WORLD));
  PetscCallMPI(MPI_Allreduce(q, gq, np, MPIU_REAL, MPI_SUM, PETSC_COMM_WORLD));
  PetscCallMPI(MPI_Allreduce(&ain, &r->ain, 1, MPIU_REAL, MPI_SUM, PETSC_COMM_WORLD));
  r->qmin = PETSC_MAX_REAL, r->qmax = -PETSC_MAX_REAL;
  for (PetscInt k = 0; k < (bz == DM_BOUNDARY_PERIODIC ? N[2] : np); k++) r->qmin = PetscMin(r->qmin, gq[k]), r->qmax = PetscMax(r->qmax, gq[k]);
  PetscCall(PetscFree2(q, gq));
  r->Q       = glob[0] / N[2] * hx[0] * hx[1];
  r->uclosed = glob[1];
  r->nclosed = (PetscInt)glob[2];
  r->umax    = gext[0];
  r->umin    = -gext[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One steady pipe at n cells across the diameter; tilted: case (b). */
static PetscErrorCode RunPipe(PetscInt n, PetscBool tilted, PipeResult *r)
{
  Domain          dom = {0};
  Fluid           fl;
  FluidStats      st;
  const PetscReal R = 0.5, D = 2 * R, h = D / n, G = 0.025;
  Pipe            pipe = {R, 0, 1, 0};

  PetscFunctionBeginUser;
  if (tilted) {
    const PetscReal Lz = 2.5 * D, Lx = Lz * PetscTanReal(PETSC_PI / 6);
    const PetscInt  Nx = (PetscInt)PetscFloorReal(Lx / h + 0.5);
    pipe.s = 0.5, pipe.c = PetscSqrtReal(3.0) / 2, pipe.per = Lz / 2;
    PetscCall(SetOptReal3("-domain_lo", 0, -R - 2 * h, 0));
    PetscCall(SetOptReal3("-domain_hi", Lx, R + 2 * h, Lz));
    PetscCall(SetOpt("-domain_periodic_x", "1"));
    PetscCall(SetOptInt("-da_grid_x", Nx));
    PetscCall(SetOptInt("-da_grid_z", (PetscInt)PetscFloorReal(Lz / h + 0.5)));
  } else {
    PetscCall(SetOptReal3("-domain_lo", -R - 2 * h, -R - 2 * h, 0));
    PetscCall(SetOptReal3("-domain_hi", R + 2 * h, R + 2 * h, 4 * h));
    PetscCall(SetOpt("-domain_periodic_x", "0"));
    PetscCall(SetOptInt("-da_grid_x", n + 4));
    PetscCall(SetOptInt("-da_grid_z", 4));
  }
  PetscCall(SetOptInt("-da_grid_y", n + 4));
  PetscCall(SetOptReal3("-fluid_pressure_gradient", -G * pipe.s, 0, -G * pipe.c));
  PetscCall(DomainCreate(PETSC_COMM_WORLD, 1.0, 1, &dom));
  PetscCall(FluidCreate(&dom, &fl));
  PetscCall(FluidSetFromOptions(fl));
  PetscCall(FluidSetVessel(fl, PipeLevel, &pipe));
  PetscCall(FluidSetUp(fl));
  for (PetscInt s = 0; s < 6; s++) PetscCall(FluidStep(fl, 100 * h, &st));
  PetscCall(PipeMeasure(fl, r));
  r->div   = st.div_max;
  r->its   = st.poisson_its;
  r->rnorm = st.poisson_rnorm;
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static void Plug(const PetscReal x[3], PetscReal v[3], void *ctx)
{
  (void)x, (void)ctx;
  v[0] = v[1] = 0;
  v[2]        = 0.01;
}

/* Writes a frame of the fluid and compares its /fluid/vessel, read back on every rank, with the
 * open-volume fractions of the owned cells: the largest difference. */
static PetscErrorCode CheckVesselOutput(Domain *dom, Fluid fl, PetscReal *maxdiff)
{
  Io                 io;
  Vec                vol;
  DM                 cda;
  const PetscScalar *v;
  PetscReal         *buf, m = 0;
  PetscInt           xs[3], xm[3], n = dom->cells[0] * dom->cells[1] * dom->cells[2];
  char               dir[PETSC_MAX_PATH_LEN], file[PETSC_MAX_PATH_LEN + 32];
  int                pid = (int)getpid();
  hid_t              f, d;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Bcast(&pid, 1, MPI_INT, 0, PETSC_COMM_WORLD));
  PetscCall(PetscSNPrintf(dir, sizeof dir, "/tmp/sable_test_pipe_%d", pid));
  PetscCall(SetOpt("-io_dir", dir));
  PetscCall(SetOpt("-io_interval", "1"));
  PetscCall(IoCreate(PETSC_COMM_WORLD, &io));
  PetscCall(IoSetFromOptions(io));
  PetscCall(IoFrameBegin(io, 0.0, 0));
  PetscCall(FluidWriteOutput(fl, io));
  PetscCall(IoFrameEnd(io));
  PetscCall(IoDestroy(&io));
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  PetscCall(PetscSNPrintf(file, sizeof file, "%s/sable_000000.h5", dir));
  PetscCall(PetscMalloc1(n, &buf));
  f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  PetscCheck(f >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot open %s", file);
  d = H5Dopen2(f, "/fluid/vessel", H5P_DEFAULT);
  PetscCheck(d >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s has no /fluid/vessel", file);
  SableCallH5(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf));
  SableCallH5(H5Dclose(d));
  SableCallH5(H5Fclose(f));
  PetscCall(FluidGetDMs(fl, &cda, NULL));
  PetscCall(FluidGetOpenFractions(fl, &vol, NULL));
  PetscCall(DMDAGetCorners(cda, &xs[0], &xs[1], &xs[2], &xm[0], &xm[1], &xm[2]));
  PetscCall(VecGetArrayRead(vol, &v));
  for (PetscInt k = xs[2], o = 0; k < xs[2] + xm[2]; k++)
    for (PetscInt j = xs[1]; j < xs[1] + xm[1]; j++)
      for (PetscInt i = xs[0]; i < xs[0] + xm[0]; i++, o++) m = PetscMax(m, PetscAbsReal(buf[(k * dom->cells[1] + j) * dom->cells[0] + i] - PetscRealPart(v[o])));
  PetscCall(VecRestoreArrayRead(vol, &v));
  PetscCall(PetscFree(buf));
  PetscCallMPI(MPI_Allreduce(&m, maxdiff, 1, MPIU_REAL, MPI_MAX, PETSC_COMM_WORLD));
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  if (pid == (int)getpid()) PetscCall(PetscRMTree(dir)); /* rank 0 (its pid): the frame's files */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A new ownership of the domain (see RunPipeVariant) and the fluid moved onto it. */
static PetscErrorCode Reown(Domain *dom, Fluid fl)
{
  const PetscInt *l0[3];
  PetscInt       *l[3], k = 0;
  PetscBool       cut;

  PetscFunctionBeginUser;
  PetscCall(DMDAGetOwnershipRanges(dom->da, &l0[0], &l0[1], &l0[2]));
  for (int d = 0; d < 3; d++)
    if (dom->nranks[d] > dom->nranks[k]) k = d;
  for (int d = 0; d < 3; d++) {
    PetscCall(PetscMalloc1(dom->nranks[d], &l[d]));
    for (PetscInt r = 0; r < dom->nranks[d]; r++) l[d][r] = l0[d][r];
  }
  if (dom->nranks[k] > 1 && l[k][dom->nranks[k] - 1] > 2) l[k][0]++, l[k][dom->nranks[k] - 1]--;
  PetscCall(DomainSetOwnership(dom, l));
  PetscCall(FluidRedistribute(fl));
  PetscCall(FluidVesselActive(fl, &cut));
  PetscCheck(cut, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "the vessel is lost after FluidRedistribute");
  for (int d = 0; d < 3; d++) PetscCall(PetscFree(l[d]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The z-pipe at 8 cells across with: 0, the explicit viscous term (adaptive dt, 100 steps) from
 * variant 3's steady state, which it must keep (the explicit and implicit operators agree, and
 * a step above the true stability limit would blow the stiffest mode up); 1, slip walls, a plug flow u_z =
 * 0.01 m/s without driving, 3 implicit steps; 2, an inlet at zlo (superficial 0.01 m/s) and an
 * outlet at zhi over 8 cells along z, 5 implicit steps; 3 and 4, 8 implicit steps of the driven
 * pipe, 4 with a new ownership after the fourth (one cell moved from the last rank column to the
 * first along the most divided axis; FluidRedistribute computes the vessel again). */
static Vec steady_u, steady_p; /* variant 3's final state, variant 0's start */

static PetscErrorCode RunPipeVariant(int kind, PipeResult *r, PetscInt *steps)
{
  Domain          dom = {0};
  Fluid           fl;
  FluidStats      st;
  const PetscReal R = 0.5, h = 1.0 / 8;
  Pipe            pipe = {kind == 0 || kind >= 3 ? 3.83 * h : R, 0, 1, 0}; /* 3.83 h: the wall 0.024 h from the face (1.5, 3.5) h along y, theta clamped */

  PetscFunctionBeginUser;
  PetscCall(SetOptReal3("-domain_lo", -R - 2 * h, -R - 2 * h, 0));
  PetscCall(SetOptReal3("-domain_hi", R + 2 * h, R + 2 * h, (kind == 2 ? 8 : 4) * h));
  PetscCall(SetOpt("-domain_periodic_x", "0"));
  PetscCall(SetOptInt("-da_grid_x", 12));
  PetscCall(SetOptInt("-da_grid_y", 12));
  PetscCall(SetOptInt("-da_grid_z", kind == 2 ? 8 : 4));
  PetscCall(SetOptReal3("-fluid_pressure_gradient", 0, 0, kind == 0 || kind >= 3 ? -0.025 : 0));
  PetscCall(SetOpt("-fluid_viscous", kind == 0 ? "explicit" : "implicit"));
  if (kind == 0) PetscCall(SetOpt("-fluid_adaptive_dt", "1"));
  if (kind == 0) PetscCall(SetOpt("-fluid_viscous_number_max", "1")); /* the stability edge: the wall links' rows must be counted */
  if (kind == 1) PetscCall(SetOpt("-fluid_vessel_wall", "slip"));
  if (kind == 2) {
    PetscCall(SetOpt("-domain_periodic_z", "0"));
    PetscCall(SetOpt("-fluid_bc_zlo", "inlet"));
    PetscCall(SetOpt("-fluid_bc_zlo_velocity", "0,0,0.01"));
    PetscCall(SetOpt("-fluid_bc_zhi", "outlet"));
  }
  PetscCall(DomainCreate(PETSC_COMM_WORLD, 1.0, 1, &dom));
  PetscCall(FluidCreate(&dom, &fl));
  PetscCall(FluidSetFromOptions(fl));
  PetscCall(FluidSetVessel(fl, PipeLevel, &pipe));
  PetscCall(FluidSetUp(fl));
  if (kind == 1) PetscCall(FluidSetVelocityFunction(fl, Plug, NULL));
  *steps = 0;
  if (kind == 0) { /* from the implicit steady state of variant 3: 100 explicit adaptive steps */
    Vec u, p;
    PetscCall(FluidGetVelocity(fl, &u));
    PetscCall(FluidGetPressure(fl, &p));
    PetscCall(VecCopy(steady_u, u));
    PetscCall(VecCopy(steady_p, p));
    for (; *steps < 100; (*steps)++) PetscCall(FluidStep(fl, 1.0, &st));
  } else
    for (; *steps < (kind == 1 ? 3 : kind == 2 ? 5
                                               : 8);
         (*steps)++) {
      PetscCall(FluidStep(fl, 0.5, &st));
      if (kind == 4 && *steps == 3) PetscCall(Reown(&dom, fl));
    }
  if (kind == 3) { /* keep the steady state for variant 0 */
    Vec u, p;
    PetscCall(FluidGetVelocity(fl, &u));
    PetscCall(FluidGetPressure(fl, &p));
    PetscCall(VecDuplicate(u, &steady_u));
    PetscCall(VecDuplicate(p, &steady_p));
    PetscCall(VecCopy(u, steady_u));
    PetscCall(VecCopy(p, steady_p));
  }
  PetscCall(PipeMeasure(fl, r));
  r->div = st.div_max;
  if (kind == 2) PetscCall(CheckVesselOutput(&dom, fl, &r->outdiff));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscCall(PetscOptionsClearValue(NULL, "-fluid_adaptive_dt"));
  PetscCall(PetscOptionsClearValue(NULL, "-fluid_viscous_number_max"));
  PetscCall(PetscOptionsClearValue(NULL, "-fluid_vessel_wall"));
  PetscCall(PetscOptionsClearValue(NULL, "-fluid_bc_zlo"));
  PetscCall(PetscOptionsClearValue(NULL, "-fluid_bc_zlo_velocity"));
  PetscCall(PetscOptionsClearValue(NULL, "-fluid_bc_zhi"));
  PetscCall(SetOpt("-domain_periodic_z", "1"));
  PetscCall(SetOpt("-fluid_viscous", "implicit"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static void TaylorGreen(const PetscReal x[3], PetscReal v[3], void *ctx)
{
  (void)ctx;
  v[0] = PetscSinReal(x[0]) * PetscCosReal(x[1]) * PetscCosReal(x[2]);
  v[1] = -PetscCosReal(x[0]) * PetscSinReal(x[1]) * PetscCosReal(x[2]);
  v[2] = 0.1 * PetscSinReal(x[2]);
}

static PetscReal One(const PetscReal x[3], void *ctx)
{
  (void)x, (void)ctx;
  return 1;
}

/* Three steps of a walled box from a Taylor-Green field, with or without a vessel phi = 1. */
static PetscErrorCode RunBox(PetscBool vessel, Vec *u, Vec *p, PetscBool *cut, PetscBool *null_fractions)
{
  Domain     dom = {0};
  Fluid      fl;
  FluidStats st;
  Vec        fu, fp, vol, area;

  PetscFunctionBeginUser;
  PetscCall(DomainCreate(PETSC_COMM_WORLD, 1.0, 1, &dom));
  PetscCall(FluidCreate(&dom, &fl));
  PetscCall(FluidSetFromOptions(fl));
  if (vessel) PetscCall(FluidSetVessel(fl, One, NULL));
  PetscCall(FluidSetUp(fl));
  PetscCall(FluidVesselActive(fl, cut));
  PetscCall(FluidGetOpenFractions(fl, &vol, &area));
  *null_fractions = (PetscBool)(!vol && !area);
  PetscCall(FluidSetVelocityFunction(fl, TaylorGreen, NULL));
  for (int s = 0; s < 3; s++) PetscCall(FluidStep(fl, 0.02, &st));
  PetscCall(FluidGetVelocity(fl, &fu));
  PetscCall(FluidGetPressure(fl, &fp));
  PetscCall(VecDuplicate(fu, u));
  PetscCall(VecCopy(fu, *u));
  PetscCall(VecDuplicate(fp, p));
  PetscCall(VecCopy(fp, *p));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  const PetscInt  ns[2][3] = {{8, 16, 32}, {8, 12, 16}};
  const PetscReal R = 0.5, Qex = PETSC_PI * R * R * R * R * 0.025 / 8;
  PipeResult      r[2][3];
  const char     *name[2] = {"z", "tilted"};

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(SetOpt("-domain_periodic_z", "1"));
  PetscCall(SetOpt("-fluid_density", "1"));
  PetscCall(SetOpt("-fluid_viscosity", "1"));
  PetscCall(SetOpt("-fluid_viscous", "implicit"));
  PetscCall(SetOpt("-fluid_viscous_pc_type", "hypre")); /* dt nu/h^2 up to 3200: Jacobi would need hundreds of iterations */
  PetscCall(SetOpt("-fluid_poisson_ksp_rtol", "1e-10"));
  for (int t = 0; t < 2; t++) {
    PetscReal err[3];
    for (int i = 0; i < 3; i++) {
      PetscLogDouble t0, t1;
      PetscCall(PetscTime(&t0));
      PetscCall(RunPipe(ns[t][i], (PetscBool)t, &r[t][i]));
      PetscCall(PetscTime(&t1));
      r[t][i].wall = t1 - t0;
      err[i]       = PetscAbsReal(r[t][i].Q - Qex) / Qex;
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "# pipe %s, %d cells across: Q %.8e (exact %.8e), relative error %.3e; max continuity residual %.2e 1/s (Poisson its %d, residual %.2e); %d closed faces, max |u| there %g; %.2f s\n", name[t], (int)ns[t][i], (double)r[t][i].Q, (double)Qex, (double)err[i], (double)r[t][i].div, (int)r[t][i].its, (double)r[t][i].rnorm, (int)r[t][i].nclosed, (double)r[t][i].uclosed, (double)r[t][i].wall));
    }
    const PetscReal o1 = PetscLogReal(err[0] / err[1]) / PetscLogReal((PetscReal)ns[t][1] / ns[t][0]), o2 = PetscLogReal(err[1] / err[2]) / PetscLogReal((PetscReal)ns[t][2] / ns[t][1]), o = PetscLogReal(err[0] / err[2]) / PetscLogReal((PetscReal)ns[t][2] / ns[t][0]);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "# pipe %s: observed order %.2f (%d -> %d), %.2f (%d -> %d)\n", name[t], (double)o1, (int)ns[t][0], (int)ns[t][1], (double)o2, (int)ns[t][1], (int)ns[t][2]));
    PetscCall(CheckClose(CheckName("pipe_%s_16_cells_flow_rate", name[t]), r[t][t ? 2 : 1].Q, Qex, 1e-2));
    PetscCall(CheckAtLeast(CheckName("pipe_%s_order_8_%d", name[t], (int)ns[t][2]), o, 1.5));
    for (int i = 0; i < 3; i++) {
      PetscCall(CheckBelow(CheckName("pipe_%s_%d_continuity_residual", name[t], (int)ns[t][i]), r[t][i].div, 1e-8));
      PetscCall(CheckEqualReal(CheckName("pipe_%s_%d_closed_face_velocity", name[t], (int)ns[t][i]), r[t][i].uclosed, 0));
    }
  }
  { /* the explicit viscous term (and its stability number with the wall links), slip walls, inlet */
    PipeResult v[5];
    PetscInt   steps[5];
    const int  order[5] = {3, 4, 0, 1, 2};
    for (int i = 0; i < 5; i++) {
      PetscLogDouble t0, t1;
      const int      k = order[i];
      PetscCall(PetscTime(&t0));
      PetscCall(RunPipeVariant(k, &v[k], &steps[k]));
      PetscCall(PetscTime(&t1));
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "# variant %d: %.2f s\n", k, (double)(t1 - t0)));
    }
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "# pipe z explicit viscous, 8 cells across: Q %.10e after %d adaptive steps from the implicit steady %.10e\n", (double)v[0].Q, (int)steps[0], (double)v[3].Q));
    PetscCall(CheckClose("pipe_z_explicit_viscous_keeps_steady_flow", v[0].Q, v[3].Q, 1e-5));
    PetscCall(VecDestroy(&steady_u));
    PetscCall(VecDestroy(&steady_p));
    CheckDetail("u_z on the open faces in [%.15g, %.15g]", (double)v[1].umin, (double)v[1].umax);
    PetscCall(CheckBelow("pipe_slip_plug_flow_kept", PetscMax(v[1].umax - 0.01, 0.01 - v[1].umin) / 0.01, 1e-10));
    CheckDetail("open inlet area %.6g m^2 (pi R^2 = %.6g); plane fluxes in [%.15g, %.15g]", (double)v[2].ain, (double)(PETSC_PI * R * R), (double)v[2].qmin, (double)v[2].qmax);
    PetscCall(CheckBelow("pipe_inlet_flux_every_plane", PetscMax(PetscAbsReal(v[2].qmax - 0.01 * v[2].ain), PetscAbsReal(v[2].qmin - 0.01 * v[2].ain)) / (0.01 * v[2].ain), 1e-9));
    PetscCall(CheckEqualReal("pipe_inlet_closed_face_velocity", v[2].uclosed, 0));
    PetscCall(CheckClose("pipe_inlet_open_area", v[2].ain, PETSC_PI * R * R, 5e-3));
    PetscCall(CheckEqualReal("pipe_output_vessel_field", v[2].outdiff, 0));
    CheckDetail("continuity residual after %.2e 1/s", (double)v[4].div);
    PetscCall(CheckClose("pipe_redistributed_same_flow", v[4].Q, v[3].Q, 1e-9));
  }
  { /* the box, with a vessel that cuts nothing: the same bits */
    Vec       u0, p0, u1, p1;
    PetscBool cut0, cut1, null0, null1, eu, ep;
    PetscCall(SetOptReal3("-domain_lo", 0, 0, 0));
    PetscCall(SetOptReal3("-domain_hi", 2 * PETSC_PI, 2 * PETSC_PI, 2 * PETSC_PI));
    PetscCall(SetOpt("-domain_periodic_x", "0"));
    PetscCall(SetOpt("-domain_periodic_z", "0"));
    PetscCall(SetOpt("-da_grid_x", "8"));
    PetscCall(SetOpt("-da_grid_y", "8"));
    PetscCall(SetOpt("-da_grid_z", "8"));
    PetscCall(SetOpt("-fluid_pressure_gradient", "0.1,0,0"));
    PetscCall(SetOpt("-fluid_viscous", "explicit"));
    PetscCall(RunBox(PETSC_FALSE, &u0, &p0, &cut0, &null0));
    PetscCall(RunBox(PETSC_TRUE, &u1, &p1, &cut1, &null1));
    PetscCall(VecEqual(u0, u1, &eu));
    PetscCall(VecEqual(p0, p1, &ep));
    PetscCall(CheckTrue("box_vessel_phi_1_not_active", (PetscBool)(!cut1 && null1), cut1 ? "the vessel cuts the grid" : "inactive, fractions NULL"));
    PetscCall(CheckTrue("box_vessel_phi_1_same_bits", (PetscBool)(eu && ep), eu && ep ? "velocity and pressure identical" : "differ"));
    PetscCall(VecDestroy(&u0));
    PetscCall(VecDestroy(&p0));
    PetscCall(VecDestroy(&u1));
    PetscCall(VecDestroy(&p1));
  }
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
