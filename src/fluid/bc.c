/* Fluid boundary conditions, one per domain face: periodic (from -domain_periodic_*), no-slip
 * wall, free-slip wall, uniform velocity inlet, pressure outlet. They enter the discretisation
 * only through two ghost layers of the local arrays, filled axis by axis (x, then y over the
 * x-ghosts, then z) so that edge and corner ghosts do not depend on the decomposition:
 *   normal component, boundary face b, ghost faces b -+ m:  wall/slip: -u(b +- m) (u(b) = 0),
 *     inlet: U_n / eps_f, outlet: u(b) (zero gradient; u(b) itself is an unknown of the
 *     projection). U_n is the SUPERFICIAL velocity (the volume flux per unit area) and eps_f the
 *     face porosity of the mass divergence (the cell next to the face: cell ghosts are even), so
 *     the flux eps_f u(b) through every inlet face is U_n whatever the solids next to it; the
 *     porosity is that of the velocity's own level (FluidFillVelocityGhosts' eps);
 *   tangential components, ghost cell mirrored from interior cell m': wall: -u, slip: +u,
 *     inlet: 2 U_t - u, outlet: +u;
 *   cell fields: even mirror, except odd about the outlet value at outlets for p and phi
 *     (Dirichlet p = -fluid_outlet_pressure on the outlet face).
 * Options: -fluid_bc_{x,y,z}{lo,hi} wall|slip|inlet|outlet, -fluid_bc_{x,y,z}{lo,hi}_velocity
 * (m/s), -fluid_outlet_pressure (Pa). */
#include "fluid/fluid_impl.h"
#include <petsc/private/petscimpl.h> /* PetscObjectStateGet: refill eps_old's ghosts only when it changed */

const char *const FluidBCNames[] = {"periodic", "wall", "slip", "inlet", "outlet", "FluidBCType", "FLUID_BC_", NULL};

/* The face options by axis and side, written out so that grep (and the option lists the Makefile
 * builds from the sources: tools/gen-options.sh) finds them; the enum is read as
 * SableOptionsEnum(FluidBCOption[d][s], ...), which tells the lists that these take words. */
static const char *const FluidBCOption[3][2]         = {{"-fluid_bc_xlo", "-fluid_bc_xhi"}, {"-fluid_bc_ylo", "-fluid_bc_yhi"}, {"-fluid_bc_zlo", "-fluid_bc_zhi"}};
static const char *const FluidBCVelocityOption[3][2] = {{"-fluid_bc_xlo_velocity", "-fluid_bc_xhi_velocity"}, {"-fluid_bc_ylo_velocity", "-fluid_bc_yhi_velocity"}, {"-fluid_bc_zlo_velocity", "-fluid_bc_zhi_velocity"}};

PetscErrorCode FluidSetFromOptionsBC(Fluid fl)
{
  const char *ax = "xyz";
  PetscBool   set, any_outlet = PETSC_FALSE;

  PetscFunctionBeginUser;
  fl->bc.has_inlet = PETSC_FALSE;
  PetscOptionsBegin(fl->comm, NULL, "Fluid boundary conditions", NULL);
  PetscCall(SableOptionsReal("-fluid_outlet_pressure", "Pressure on outlet faces", "Pa", NULL, fl->bc.p_out, &fl->bc.p_out, NULL));
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) {
      FluidBCType t   = fl->bc.face[d][s].type;
      PetscInt    k   = t;
      const char *opt = FluidBCOption[d][s], *optv = FluidBCVelocityOption[d][s];
      PetscCall(SableOptionsEnum(FluidBCOption[d][s], "Boundary condition of this face: wall (no-slip), slip, inlet, outlet; periodic axes are set by -domain_periodic_*", FluidBCNames, 5, k, &k, &set));
      t = (FluidBCType)k;
      PetscCheck(!set || fl->dom->periodic[d] == (t == FLUID_BC_PERIODIC), fl->comm, PETSC_ERR_ARG_WRONG, "%s %s: the %c axis is %speriodic (-domain_periodic_%c); valid values here: %s", opt, FluidBCNames[t], ax[d], fl->dom->periodic[d] ? "" : "not ", ax[d], fl->dom->periodic[d] ? "periodic" : "wall, slip, inlet, outlet");
      fl->bc.face[d][s].type = t;
      PetscCall(SableOptionsRealN(optv, "Inlet velocity on this face", "m/s", fl->bc.face[d][s].vel, 3, 3, &set));
      PetscCheck(!set || t == FLUID_BC_INLET, fl->comm, PETSC_ERR_ARG_WRONG, "%s is given but %s is %s, not inlet", optv, opt, FluidBCNames[t]);
      if (t == FLUID_BC_OUTLET) any_outlet = PETSC_TRUE;
      if (t == FLUID_BC_INLET) fl->bc.has_inlet = PETSC_TRUE;
    }
  PetscOptionsEnd();
  fl->pois.singular = any_outlet ? PETSC_FALSE : PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidGetBC(Fluid fl, int d, int side, FluidBCType *type)
{
  PetscFunctionBeginUser;
  PetscCheck(d >= 0 && d < 3 && (side == 0 || side == 1), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "face %d,%d: the axis must be in [0,2], the side 0 or 1", d, side);
  *type = fl->bc.face[d][side].type;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The inlet's normal face value U_n / eps_f in the column of tangential indices q (q[d] unused),
 * eps the ghosted cell porosity; columns beyond the cell ghosts (the face DMDA's extra ghost
 * point) take the last ghost cell's. */
static inline PetscScalar fluid_inlet_normal(const FluidGrid *g, PetscReal vn, const PetscScalar *eps, int d, int s, const PetscInt q[3])
{
  PetscInt r[3];
  for (int e = 0; e < 3; e++) r[e] = PetscMin(PetscMax(q[e], g->gcs[e]), g->gcs[e] + g->gcm[e] - 1);
  r[d]             = s ? g->N[d] - 1 : 0;
  const PetscInt c = FluidCellOff(g, r[0], r[1], r[2]);
  return vn / (0.5 * (eps[c] + eps[c + (s ? 1 : -1) * g->cs[d]]));
}

/* Fills the ghosts of one non-periodic face of the local face array. */
static void FluidFillVelocityFace(Fluid fl, PetscScalar *u, const PetscScalar *eps, int d, int s)
{
  const FluidGrid *g  = &fl->g;
  const FluidBC   *bc = &fl->bc.face[d][s];
  const int        a = (d + 1) % 3, b = (d + 2) % 3;
  const PetscInt   N = g->N[d], bnd = s ? N : 0, sg = s ? 1 : -1;
  PetscInt         idx[3];

  for (idx[b] = g->gfs[b]; idx[b] < g->gfs[b] + g->gfm[b]; idx[b]++)
    for (idx[a] = g->gfs[a]; idx[a] < g->gfs[a] + g->gfm[a]; idx[a]++) {
      PetscInt q[3]     = {idx[0], idx[1], idx[2]};
      q[d]              = bnd;
      const PetscInt f0 = FluidFaceOff(g, q[0], q[1], q[2]), st = g->fs[d];
      /* a patch's point: its condition, its normal velocity, no tangential inflow */
      const PetscInt    pt   = bc->pkind ? fluid_face_point(fl, d, q) : 0;
      const FluidBCType type = bc->pkind && bc->pkind[pt] ? (FluidBCType)bc->pkind[pt] : bc->type;
      const PetscReal  *vel  = bc->pkind && bc->pkind[pt] ? (const PetscReal[3]){0, 0, 0} : bc->vel;
      /* normal component: boundary face value, then ghost faces bnd + sg*m */
      if (type == FLUID_BC_WALL || type == FLUID_BC_SLIP) u[f0 + d] = 0;
      if (type == FLUID_BC_INLET) u[f0 + d] = fluid_inlet_normal(g, bc->pkind && bc->pkind[pt] ? bc->pvn[pt] : bc->vel[d], eps, d, s, q);
      for (PetscInt m = 1; m <= 2; m++) {
        PetscScalar *gh = &u[f0 + sg * m * st + d], in = u[f0 - sg * m * st + d];
        switch (type) {
        case FLUID_BC_INLET:
          *gh = u[f0 + d];
          break;
        case FLUID_BC_OUTLET:
          *gh = u[f0 + d];
          break;
        default:
          *gh = -in;
          break;
        }
      }
      /* tangential components: cell-centred along d; interior cell m' mirrors to ghost */
      const PetscInt c0 = s ? FluidFaceOff(g, q[0], q[1], q[2]) - st : f0; /* first interior */
      for (int c = 0; c < 3; c++) {
        if (c == d) continue;
        for (PetscInt m = 0; m <= 1; m++) {
          PetscScalar in = u[c0 - sg * m * st + c], *gh = &u[c0 + sg * (m + 1) * st + c];
          switch (type) {
          case FLUID_BC_WALL:
            *gh = -in;
            break;
          case FLUID_BC_INLET:
            *gh = 2 * vel[c] - in;
            break;
          default:
            *gh = in;
            break;
          }
        }
      }
    }
}

/* eps: the ghosted porosity of the velocity's level (read only at inlets; NULL without them). */
PetscErrorCode FluidFillVelocityGhosts(Fluid fl, PetscScalar *u, const PetscScalar *eps)
{
  const FluidGrid *g = &fl->g;

  PetscFunctionBeginUser;
  for (int d = 0; d < 3; d++) {
    if (FluidPeriodic(fl, d)) continue;
    if (g->xs[d] == 0) FluidFillVelocityFace(fl, u, eps, d, 0);
    if (g->xs[d] + g->xm[d] == g->N[d]) FluidFillVelocityFace(fl, u, eps, d, 1);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The ghosted porosity of the level of fl->u into epsoldloc: eps_old (a step ends
 * with eps_old = eps). Without force, filled only with inlets and when eps_old changed since the
 * last fill (its object state). */
PetscErrorCode FluidLocalPorosityOld(Fluid fl, PetscBool force)
{
  PetscObjectState st;

  PetscFunctionBeginUser;
  if (!force && !fl->bc.has_inlet) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscObjectStateGet((PetscObject)fl->fld.eps_old, &st));
  if (!force && st == fl->fld.epsold_state) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(FluidLocalCell(fl, fl->fld.eps_old, fl->fld.epsoldloc, PETSC_FALSE, 0.0));
  fl->fld.epsold_state = st;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. At the end of a step, after eps_old = eps: with inlets, epsoldloc takes epsloc (the
 * same values, no communication) and the inlet faces of fl->u the new level's U_n / eps_f. */
PetscErrorCode FluidInletsEndStep(Fluid fl)
{
  PetscFunctionBeginUser;
  if (!fl->bc.has_inlet) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(VecCopy(fl->fld.epsloc, fl->fld.epsoldloc));
  PetscCall(PetscObjectStateGet((PetscObject)fl->fld.eps_old, &fl->fld.epsold_state));
  PetscCall(FluidInletFaceValues(fl, fl->fld.u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidFillCellGhosts(Fluid fl, PetscScalar *v, PetscInt ghost, PetscReal outlet_value)
{
  const FluidGrid *g = &fl->g;

  PetscFunctionBeginUser;
  for (int d = 0; d < 3; d++) {
    const int a = (d + 1) % 3, b = (d + 2) % 3;
    if (FluidPeriodic(fl, d)) continue;
    for (int s = 0; s < 2; s++) {
      const PetscInt  sg = s ? 1 : -1, first = s ? g->N[d] - 1 : 0;
      const FluidBC  *bc  = &fl->bc.face[d][s];
      const PetscBool odd = (PetscBool)(ghost != FLUID_GHOST_EVEN && bc->type == FLUID_BC_OUTLET);
      PetscInt        idx[3];
      if (s == 0 && g->xs[d] != 0) continue;
      if (s == 1 && g->xs[d] + g->xm[d] != g->N[d]) continue;
      for (idx[b] = g->gcs[b]; idx[b] < g->gcs[b] + g->gcm[b]; idx[b]++)
        for (idx[a] = g->gcs[a]; idx[a] < g->gcs[a] + g->gcm[a]; idx[a]++) {
          PetscInt q[3]     = {idx[0], idx[1], idx[2]};
          q[d]              = first;
          const PetscInt c0 = FluidCellOff(g, q[0], q[1], q[2]), st = g->cs[d];
          PetscBool      o  = odd;
          PetscReal      ov = outlet_value;
          if (bc->pkind && ghost != FLUID_GHOST_EVEN) { /* a patch's point: odd at its outlets only, about its own pressure */
            const PetscInt pt = fluid_face_point(fl, d, q);
            if (bc->pkind[pt]) o = (PetscBool)(bc->pkind[pt] == FLUID_BC_OUTLET);
            if (bc->pkind[pt] == FLUID_BC_OUTLET && ghost == FLUID_GHOST_PRESSURE) ov = bc->pp[pt];
          }
          for (PetscInt m = 0; m <= 1; m++) {
            PetscScalar in            = v[c0 - sg * m * st];
            v[c0 + sg * (m + 1) * st] = o ? 2 * ov - in : in;
          }
        }
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* epsloc: the ghosted porosity of u's level, current (FluidLocalCell, FluidLocalPorosityOld). */
PetscErrorCode FluidLocalVelocity(Fluid fl, Vec u, Vec uloc, Vec epsloc)
{
  PetscScalar       *a;
  const PetscScalar *e = NULL;

  PetscFunctionBeginUser;
  PetscCall(DMGlobalToLocal(fl->g.fda, u, INSERT_VALUES, uloc));
  PetscCall(VecGetArray(uloc, &a));
  if (fl->bc.has_inlet) PetscCall(VecGetArrayRead(epsloc, &e));
  PetscCall(FluidFillVelocityGhosts(fl, a, e));
  if (fl->bc.has_inlet && fl->ves.cut) PetscCall(FluidVesselZeroClosed(fl, a)); /* inlet faces the vessel closes */
  if (fl->bc.has_inlet) PetscCall(VecRestoreArrayRead(epsloc, &e));
  PetscCall(VecRestoreArray(uloc, &a));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FluidLocalCell(Fluid fl, Vec v, Vec vloc, PetscInt ghost, PetscReal outlet_value)
{
  PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(DMGlobalToLocal(fl->g.cda, v, INSERT_VALUES, vloc));
  PetscCall(VecGetArray(vloc, &a));
  PetscCall(FluidFillCellGhosts(fl, a, ghost, outlet_value));
  PetscCall(VecRestoreArray(vloc, &a));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. Sets the fixed faces of a global face Vec of the level of eps_old (fl->u): wall
 * normal components 0, inlet normal components U_n / eps_f, the unused extra points of
 * tangential components 0. */
PetscErrorCode FluidBoundaryFaceValues(Fluid fl, Vec u)
{
  const FluidGrid *g = &fl->g;
  PetscScalar  ****a;
  PetscInt         idx[3];

  PetscFunctionBeginUser;
  PetscCall(DMDAVecGetArrayDOF(fl->g.fda, u, &a));
  for (idx[2] = g->xs[2]; idx[2] < g->xs[2] + g->fxm[2]; idx[2]++)
    for (idx[1] = g->xs[1]; idx[1] < g->xs[1] + g->fxm[1]; idx[1]++)
      for (idx[0] = g->xs[0]; idx[0] < g->xs[0] + g->fxm[0]; idx[0]++)
        for (int d = 0; d < 3; d++) {
          if (FluidFaceActive(fl, d, idx)) continue;
          a[idx[2]][idx[1]][idx[0]][d] = 0;
        }
  PetscCall(DMDAVecRestoreArrayDOF(fl->g.fda, u, &a));
  PetscCall(FluidInletFaceValues(fl, u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Collective. The inlet normal components U_n / eps_f of a global face Vec of the level of
 * eps_old (only the owned boundary planes). */
PetscErrorCode FluidInletFaceValues(Fluid fl, Vec u)
{
  const FluidGrid   *g = &fl->g;
  const PetscScalar *eps;
  PetscScalar    ****a;

  PetscFunctionBeginUser;
  if (!fl->bc.has_inlet) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(FluidLocalPorosityOld(fl, PETSC_FALSE));
  PetscCall(VecGetArrayRead(fl->fld.epsoldloc, &eps));
  PetscCall(DMDAVecGetArrayDOF(fl->g.fda, u, &a));
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) {
      const int      a1 = (d + 1) % 3, b1 = (d + 2) % 3;
      PetscInt       q[3];
      const FluidBC *bc = &fl->bc.face[d][s];
      if ((bc->type != FLUID_BC_INLET && !bc->pkind) || (s ? g->xs[d] + g->xm[d] != g->N[d] : g->xs[d] != 0)) continue;
      q[d] = s ? g->N[d] : 0;
      for (q[b1] = g->xs[b1]; q[b1] < g->xs[b1] + g->fxm[b1]; q[b1]++)
        for (q[a1] = g->xs[a1]; q[a1] < g->xs[a1] + g->fxm[a1]; q[a1]++) {
          const PetscBool closed = (PetscBool)(fl->ves.aloc && fl->ves.aloc[FluidFaceOff(g, q[0], q[1], q[2]) + d] == 0);
          if (!bc->pkind) a[q[2]][q[1]][q[0]][d] = closed ? 0 : fluid_inlet_normal(g, bc->vel[d], eps, d, s, q);
          else if (FluidFaceActive(fl, d, q) || q[a1] == g->N[a1] || q[b1] == g->N[b1]) continue; /* outlets, the unused extra points */
          else if (!closed && fluid_bc_at(fl, d, s, q) == FLUID_BC_INLET) a[q[2]][q[1]][q[0]][d] = fluid_inlet_normal(g, bc->pkind[fluid_face_point(fl, d, q)] ? bc->pvn[fluid_face_point(fl, d, q)] : bc->vel[d], eps, d, s, q);
          else a[q[2]][q[1]][q[0]][d] = 0;
        }
    }
  PetscCall(DMDAVecRestoreArrayDOF(fl->g.fda, u, &a));
  PetscCall(VecRestoreArrayRead(fl->fld.epsoldloc, &eps));
  PetscFunctionReturn(PETSC_SUCCESS);
}
