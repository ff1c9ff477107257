/* ranks: 1 2 */
/* Inlet and outlet patches, the face pressure and the distributor plate (src/fluid/patch.c,
 * probe.c, distributor.c) against conservation and analytic solutions. The box of
 * test_patch.opts (1 x 1 x 2 m, 8 x 8 x 16 cells, rho = 1 kg/m^3, Poisson rtol 1e-12):
 *   A. walls, a disc inlet on zlo (R = 0.3 m, 0.05 kg/s) and a rectangle outlet on the upper
 *      quarter of xhi: the inlet's mass flow measured from its face fluxes equals the set value
 *      to round-off (1e-12), the outlet's equals it to the solver tolerance (1e-8), 3 steps;
 *   B. walls, a tilted disc (normal (1,0,1), R = 0.25 m, U = 0.2 m/s) inside the domain as a
 *      volume source, the whole zhi face an outlet: the source's flow equals rho U pi R^2 to
 *      round-off (the disc's polygon keeps its area), the outlet's to the solver tolerance;
 *   B''. a horizontal disc source lying on a plane of cell faces (z = 1 m): counted once;
 *   B'. a strip of a cylinder's surface (R = 0.3 m, L = 0.5 m, U = 0.05 m/s; the whole ring and
 *      half of it) as a source: its flow equals rho U 2 pi R L (x 1/2) to round-off (the quads'
 *      chords keep the strip's area), the outflow to the solver tolerance;
 *   C. Darcy flow, periodic in x and y, eps = 0.5, beta = 100 kg m^-3 s^-1, a rectangle inlet
 *      patch over all of zlo (U = 0.1 m/s), the zhi face an outlet at 0 Pa: the pressure is
 *      linear, p(z) = beta (U/eps) (L - z), so the face pressure at z = 0 (probe, plane
 *      average, the patch's mean) equals beta (U/eps) L to the solver tolerance (1e-8);
 *   D. an empty column, periodic in x and y, inlet U = 0.5 m/s on zlo, outlet zhi, a distributor
 *      plate at z = 1 m (phi = 0.3, Cd = 0.6): the pressure drop across it equals Kunii &
 *      Levenspiel's orifice law rho/2 (U/(Cd phi))^2 to the solver tolerance (1e-8).
 * A and D again with -fluid_viscous implicit (the implicit operator reads the patches' points;
 * D in 8 steps: the implicit term spreads the plate's dip of the predicted velocity to its
 * neighbours, which the pressure absorbs in a transient that decays by ~mu/(rho h^2/dt) a step).
 *   E. a cylinder vessel (FAVOR, R = 0.4 m along z): a disc inlet on zlo wider than it
 *      (R = 0.45 m, 0.05 kg/s) and a tilted disc source inside; their mass flows equal the set
 *      values to round-off, the outflow through zhi (a_f eps u A) their sum to the solver
 *      tolerance; a vessel that closes the box outlet is refused.
 * On 2 ranks the same figures (the decomposition splits the box). */
#include "fluid_common.h"

/* Volume flow out through the zhi face (m^3/s), summed by the test itself. */
static PetscErrorCode TopFlow(Fluid fl, const Domain *dom, PetscReal *Q)
{
  DM                    cda, fda;
  Vec                   u, eps;
  const PetscScalar ****a, ***e;
  PetscInt              xs, ys, zs, xm, ym, zm, N = dom->cells[2];
  PetscReal             q = 0;

  PetscFunctionBeginUser;
  PetscCall(FluidGetDMs(fl, &cda, &fda));
  PetscCall(FluidGetVelocity(fl, &u));
  PetscCall(FluidGetPorosity(fl, &eps));
  PetscCall(DMDAGetCorners(cda, &xs, &ys, &zs, &xm, &ym, &zm));
  PetscCall(DMDAVecGetArrayDOFRead(fda, u, (void *)&a));
  PetscCall(DMDAVecGetArrayRead(cda, eps, (void *)&e));
  if (zs + zm == N)
    for (PetscInt j = ys; j < ys + ym; j++)
      for (PetscInt i = xs; i < xs + xm; i++) q += e[N - 1][j][i] * a[N][j][i][2] * dom->h[0] * dom->h[1];
  PetscCall(DMDAVecRestoreArrayRead(cda, eps, (void *)&e));
  PetscCall(DMDAVecRestoreArrayDOFRead(fda, u, (void *)&a));
  PetscCall(MPIU_Allreduce(&q, Q, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscReal Half(const PetscReal x[3], void *ctx)
{
  (void)x;
  (void)ctx;
  return 0.5;
}

static PetscErrorCode CaseA(const char *extra)
{
  Domain     dom = {0};
  Fluid      fl;
  FluidStats st;
  PetscReal  p, m[2];
  PetscInt   k;

  PetscFunctionBeginUser;
  PetscCall(TestSceneLoad(PETSC_COMM_WORLD, "test_patch.opts", "-fluid_patch_0_type inlet -fluid_patch_0_disc 0.5,0.5,0,0,0,1,0.3 -fluid_patch_0_mass_flow 0.05 -fluid_patch_1_type outlet -fluid_patch_1_rect 1,0,1.5,1,1,1.5,1,0,2"));
  PetscCall(PetscOptionsInsertString(NULL, extra));
  PetscCall(TestFluidCreate(1.0, NULL, NULL, &dom, &fl));
  for (int n = 0; n < 3; n++) PetscCall(FluidStep(fl, 0.01, &st));
  PetscCall(FluidPatchMeasure(fl, 0, &k, &p, &m[0]));
  PetscCall(FluidPatchMeasure(fl, 1, &k, &p, &m[1]));
  PetscCall(CheckClose(CheckName("patch_disc_inlet_zlo_mass_flow%s", *extra ? "_implicit_viscous" : ""), m[0], 0.05, 1e-12));
  CheckDetail("outlet mean pressure %g Pa (set 0)", (double)p);
  PetscCall(CheckClose(CheckName("patch_rect_outlet_xhi_mass_flow%s", *extra ? "_implicit_viscous" : ""), m[1], 0.05, 1e-8));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CaseB(void)
{
  Domain          dom = {0};
  Fluid           fl;
  FluidStats      st;
  PetscReal       p, m, Q;
  PetscInt        k;
  const PetscReal Qset = 0.2 * PETSC_PI * 0.25 * 0.25;

  PetscFunctionBeginUser;
  PetscCall(TestSceneLoad(PETSC_COMM_WORLD, "test_patch.opts", "-fluid_bc_zhi outlet -fluid_patch_0_type inlet -fluid_patch_0_disc 0.5,0.5,1,1,0,1,0.25 -fluid_patch_0_velocity 0.2"));
  PetscCall(TestFluidCreate(1.0, NULL, NULL, &dom, &fl));
  for (int n = 0; n < 3; n++) PetscCall(FluidStep(fl, 0.01, &st));
  PetscCall(FluidPatchMeasure(fl, 0, &k, &p, &m));
  PetscCall(TopFlow(fl, &dom, &Q));
  PetscCall(CheckClose("patch_tilted_disc_source_mass_flow", m, Qset, 1e-12));
  CheckDetail("continuity residual %.2e 1/s", (double)st.div_max);
  PetscCall(CheckClose("patch_tilted_disc_source_outlet_flow", Q, Qset, 1e-8));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* B''. a horizontal disc source on a plane of cell faces (z = 1 m): one side's cells take it. */
static PetscErrorCode CaseFlat(void)
{
  Domain          dom = {0};
  Fluid           fl;
  FluidStats      st;
  PetscReal       p, m, Q;
  PetscInt        k;
  const PetscReal Qset = 0.2 * PETSC_PI * 0.25 * 0.25;

  PetscFunctionBeginUser;
  PetscCall(TestSceneLoad(PETSC_COMM_WORLD, "test_patch.opts", "-fluid_bc_zhi outlet -fluid_patch_0_type inlet -fluid_patch_0_disc 0.5,0.5,1,0,0,1,0.25 -fluid_patch_0_velocity 0.2"));
  PetscCall(TestFluidCreate(1.0, NULL, NULL, &dom, &fl));
  PetscCall(FluidStep(fl, 0.01, &st));
  PetscCall(FluidPatchMeasure(fl, 0, &k, &p, &m));
  PetscCall(TopFlow(fl, &dom, &Q));
  PetscCall(CheckClose("patch_disc_source_on_a_face_plane_mass_flow", m, Qset, 1e-12));
  PetscCall(CheckClose("patch_disc_source_on_a_face_plane_outlet_flow", Q, Qset, 1e-8));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* B'. a strip of a cylinder's surface (axis z through (0.5, 0.5, 1), R = 0.3 m, L = 0.5 m; the
 * whole ring, then half of it) as a source of U = 0.05 m/s: flow rho U 2 pi R L (x 1/2). */
static PetscErrorCode CaseStrip(const char *angles, PetscReal share)
{
  Domain          dom = {0};
  Fluid           fl;
  FluidStats      st;
  PetscReal       p, m, Q;
  PetscInt        k;
  char            opts[256];
  const PetscReal Qset = share * 0.05 * 2 * PETSC_PI * 0.3 * 0.5;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof opts, "-fluid_bc_zhi outlet -fluid_patch_0_type inlet -fluid_patch_0_cylinder 0.5,0.5,1,0,0,1,0.3,0.5%s -fluid_patch_0_velocity 0.05", angles));
  PetscCall(TestSceneLoad(PETSC_COMM_WORLD, "test_patch.opts", opts));
  PetscCall(TestFluidCreate(1.0, NULL, NULL, &dom, &fl));
  for (int n = 0; n < 2; n++) PetscCall(FluidStep(fl, 0.01, &st));
  PetscCall(FluidPatchMeasure(fl, 0, &k, &p, &m));
  PetscCall(TopFlow(fl, &dom, &Q));
  PetscCall(CheckClose(CheckName("patch_cylinder_strip%s_source_mass_flow", *angles ? "_half" : ""), m, Qset, 1e-12));
  PetscCall(CheckClose(CheckName("patch_cylinder_strip%s_source_outlet_flow", *angles ? "_half" : ""), Q, Qset, 1e-8));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CaseC(void)
{
  Domain          dom = {0};
  Fluid           fl;
  FluidStats      st;
  Vec             beta;
  PetscReal       p, pm, m, avg[5], Ui[3];
  PetscInt        k, ni;
  const PetscReal U = 0.1, eps = 0.5, b = 100, L = 2, x0[3] = {0.3, 0.7, 0}, Uv[3] = {0, 0, U};
  const FluidSpan face = {{0, 0, 0}, {1, 1, 0}, PETSC_FALSE, "face zlo"};

  PetscFunctionBeginUser;
  PetscCall(TestSceneLoad(PETSC_COMM_WORLD, "test_patch.opts", "-domain_periodic_x -domain_periodic_y -fluid_bc_zhi outlet -fluid_patch_0_type inlet -fluid_patch_0_rect 0,0,0,1,0,0,0,1,0 -fluid_patch_0_velocity 0.1"));
  PetscCall(TestFluidCreate(1.0, Half, NULL, &dom, &fl));
  PetscCall(FluidGetDragCoefficient(fl, &beta));
  PetscCall(VecSet(beta, b));
  { /* the inlet's face points carry the force of the half cell above them per V_cell (fluid.h): b / 2 */
    DM              cda, fda;
    PetscScalar ****a;
    PetscInt        xs, ys, zs, xm, ym, zm;
    PetscCall(FluidGetDMs(fl, &cda, &fda));
    PetscCall(DMDAGetCorners(cda, &xs, &ys, &zs, &xm, &ym, &zm));
    PetscCall(DMDAVecGetArrayDOF(fda, beta, (void *)&a));
    if (zs == 0)
      for (PetscInt j = ys; j < ys + ym; j++)
        for (PetscInt i = xs; i < xs + xm; i++) a[0][j][i][2] = 0.5 * b;
    PetscCall(DMDAVecRestoreArrayDOF(fda, beta, (void *)&a));
  }
  PetscCall(FluidGetInletVelocity(fl, Ui, &ni)); /* the patch's flow over the face: Uv */
  PetscCall(CheckClose("patch_inlet_velocity_for_a_uniform_start", Ui[2], Uv[2], 1e-12));
  PetscCall(FluidSetSuperficialVelocity(fl, Ui));
  for (int n = 0; n < 2; n++) PetscCall(FluidStep(fl, 0.01, &st));
  PetscCall(FluidProbePressure(fl, x0, &p));
  PetscCall(FluidAverageFields(fl, 1, &face, PETSC_FALSE, avg));
  PetscCall(FluidPatchMeasure(fl, 0, &k, &pm, &m));
  CheckDetail("the centre row reads %g Pa", (double)(b * U / eps * (L - 1.0 / 16)));
  PetscCall(CheckClose("face_pressure_probe_darcy", p, b * U / eps * L, 1e-8));
  PetscCall(CheckClose("face_pressure_plane_average_darcy", avg[0], b * U / eps * L, 1e-8));
  PetscCall(CheckClose("face_pressure_patch_mean_darcy", pm, b * U / eps * L, 1e-8));
  PetscCall(CheckClose("patch_rect_inlet_zlo_mass_flow", m, U * 1.0, 1e-12));
  { /* a medium varying along z, beta_k = b (1 + 0.6 sin 1.7 k) on the face points k h (the inlet's
       k = 0 too): the inlet face's pressure less the outlet's is the whole column's momentum
       balance, h u (beta_0 + sum_{0<k<N} beta_k + beta_N / 2), u = U / eps (the outlet face's
       equation spans half a cell to its ghost); the centres' extrapolation alone misses it */
    DM              cda, fda;
    PetscScalar ****a;
    PetscInt        xs, ys, zs, xm, ym, zm, N = dom.cells[2];
    const PetscReal h   = L / N;
    PetscReal       ref = 0;
    PetscCall(FluidGetDMs(fl, &cda, &fda));
    PetscCall(DMDAGetCorners(fda, &xs, &ys, &zs, &xm, &ym, &zm)); /* the owned face points: the last rank along z holds k = N */
    PetscCall(DMDAVecGetArrayDOF(fda, beta, (void *)&a));
    for (PetscInt kk = zs; kk < zs + zm; kk++)
      for (PetscInt j = ys; j < ys + ym; j++)
        for (PetscInt i = xs; i < xs + xm; i++) a[kk][j][i][2] = b * (1 + 0.6 * PetscSinReal(1.7 * kk));
    PetscCall(DMDAVecRestoreArrayDOF(fda, beta, (void *)&a));
    for (PetscInt kk = 0; kk <= N; kk++) ref += (kk == N ? 0.5 : 1) * h * (U / eps) * b * (1 + 0.6 * PetscSinReal(1.7 * kk));
    for (int n = 0; n < 2; n++) PetscCall(FluidStep(fl, 0.01, &st));
    PetscCall(FluidProbePressure(fl, x0, &p));
    PetscCall(FluidAverageFields(fl, 1, &face, PETSC_FALSE, avg));
    PetscCall(FluidPatchMeasure(fl, 0, &k, &pm, &m));
    PetscCall(CheckClose("face_pressure_probe_darcy_varying_medium", p, ref, 1e-8));
    PetscCall(CheckClose("face_pressure_plane_average_darcy_varying_medium", avg[0], ref, 1e-8));
    PetscCall(CheckClose("face_pressure_patch_mean_darcy_varying_medium", pm, ref, 1e-8));
    PetscCall(FluidFacePressure(fl, 2, 0, &p));
    PetscCall(CheckClose("face_pressure_face_mean_darcy_varying_medium", p, ref, 1e-8));
    PetscCall(FluidFacePressure(fl, 2, 1, &p));
    PetscCall(CheckClose("face_pressure_outlet_face_mean_is_set_pressure", p + ref, ref, 1e-14));
  }
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CaseD(const char *extra)
{
  Domain          dom = {0};
  Fluid           fl;
  FluidStats      st;
  PetscReal       pb, pa;
  const PetscReal U = 0.5, phi = 0.3, cd = 0.6, xb[3] = {0.5, 0.5, 0.5}, xa[3] = {0.5, 0.5, 1.5}, Uv[3] = {0, 0, U};
  const PetscReal law = 0.5 * 1.0 * PetscSqr(U / (cd * phi));

  PetscFunctionBeginUser;
  PetscCall(TestSceneLoad(PETSC_COMM_WORLD, "test_patch.opts", "-domain_periodic_x -domain_periodic_y -fluid_bc_zlo inlet -fluid_bc_zlo_velocity 0,0,0.5 -fluid_bc_zhi outlet -fluid_distributor 1.0,0.3,0.6"));
  PetscCall(PetscOptionsInsertString(NULL, extra));
  PetscCall(TestFluidCreate(1.0, NULL, NULL, &dom, &fl));
  PetscCall(FluidSetSuperficialVelocity(fl, Uv));
  for (int n = 0; n < (*extra ? 8 : 3); n++) PetscCall(FluidStep(fl, 0.01, &st));
  PetscCall(FluidProbePressure(fl, xb, &pb));
  PetscCall(FluidProbePressure(fl, xa, &pa));
  CheckDetail("p below %g Pa, above %g Pa", (double)pb, (double)pa);
  PetscCall(CheckClose(CheckName("distributor_dp_kunii_levenspiel%s", *extra ? "_implicit_viscous" : ""), pb - pa, law, 1e-8));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A cylinder along z, radius 0.4 m, about (0.5, 0.5): phi > 0 inside. */
static PetscReal Cylinder(const PetscReal x[3], void *ctx)
{
  (void)ctx;
  return 0.4 - PetscSqrtReal(PetscSqr(x[0] - 0.5) + PetscSqr(x[1] - 0.5));
}

/* Volume flow out through the zhi face with the open-area fractions (m^3/s). */
static PetscErrorCode TopFlowFavor(Fluid fl, const Domain *dom, PetscReal *Q)
{
  DM                    cda, fda;
  Vec                   u, eps, vol, area;
  const PetscScalar ****a, ***e, ****af;
  PetscInt              xs, ys, zs, xm, ym, zm, N = dom->cells[2];
  PetscReal             q = 0;

  PetscFunctionBeginUser;
  PetscCall(FluidGetDMs(fl, &cda, &fda));
  PetscCall(FluidGetVelocity(fl, &u));
  PetscCall(FluidGetPorosity(fl, &eps));
  PetscCall(FluidGetOpenFractions(fl, &vol, &area));
  PetscCall(DMDAGetCorners(cda, &xs, &ys, &zs, &xm, &ym, &zm));
  PetscCall(DMDAVecGetArrayDOFRead(fda, u, (void *)&a));
  PetscCall(DMDAVecGetArrayDOFRead(fda, area, (void *)&af));
  PetscCall(DMDAVecGetArrayRead(cda, eps, (void *)&e));
  if (zs + zm == N)
    for (PetscInt j = ys; j < ys + ym; j++)
      for (PetscInt i = xs; i < xs + xm; i++) q += af[N][j][i][2] * e[N - 1][j][i] * a[N][j][i][2] * dom->h[0] * dom->h[1];
  PetscCall(DMDAVecRestoreArrayRead(cda, eps, (void *)&e));
  PetscCall(DMDAVecRestoreArrayDOFRead(fda, area, (void *)&af));
  PetscCall(DMDAVecRestoreArrayDOFRead(fda, u, (void *)&a));
  PetscCall(MPIU_Allreduce(&q, Q, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* E. under a cylinder vessel: a disc inlet on zlo wider than the vessel (R = 0.45 m: the faces
 * the vessel closes or cuts take their open share) and a tilted disc source, the zhi face an
 * outlet; then a vessel that closes the box outlet on xhi is refused. */
static PetscErrorCode CaseE(void)
{
  Domain         dom = {0};
  Fluid          fl;
  FluidStats     st;
  PetscReal      p, m, ms, Q;
  PetscInt       k;
  PetscBool      cut;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCall(TestSceneLoad(PETSC_COMM_WORLD, "test_patch.opts", "-fluid_bc_zhi outlet -fluid_patch_0_type inlet -fluid_patch_0_disc 0.5,0.5,0,0,0,1,0.45 -fluid_patch_0_mass_flow 0.05 -fluid_patch_1_type inlet -fluid_patch_1_disc 0.5,0.5,1,1,0,1,0.2 -fluid_patch_1_velocity 0.1"));
  PetscCall(DomainCreate(PETSC_COMM_WORLD, 1.0, 1, &dom));
  PetscCall(FluidCreate(&dom, &fl));
  PetscCall(FluidSetFromOptions(fl));
  PetscCall(FluidSetVessel(fl, Cylinder, NULL));
  PetscCall(FluidSetUp(fl));
  PetscCall(FluidVesselActive(fl, &cut));
  for (int n = 0; n < 3; n++) PetscCall(FluidStep(fl, 0.01, &st));
  PetscCall(FluidPatchMeasure(fl, 0, &k, &p, &m));
  PetscCall(FluidPatchMeasure(fl, 1, &k, &p, &ms));
  PetscCall(TopFlowFavor(fl, &dom, &Q));
  CheckDetail("vessel cuts the grid: %s", cut ? "yes" : "no");
  PetscCall(CheckClose("patch_disc_inlet_under_cylinder_vessel_mass_flow", m, 0.05, 1e-12));
  PetscCall(CheckClose("patch_source_in_cylinder_vessel_mass_flow", ms, 0.1 * PETSC_PI * 0.04, 1e-12));
  CheckDetail("continuity residual %.2e 1/s", (double)st.div_max);
  PetscCall(CheckClose("patch_cylinder_vessel_outlet_flow", Q, 0.05 + 0.1 * PETSC_PI * 0.04, 1e-8));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  /* the box outlet on xhi lies wholly in the vessel's wall */
  PetscCall(TestSceneLoad(PETSC_COMM_WORLD, "test_patch.opts", "-fluid_bc_xhi outlet -fluid_patch_0_type inlet -fluid_patch_0_disc 0.5,0.5,0,0,0,1,0.3 -fluid_patch_0_mass_flow 0.05"));
  PetscCall(DomainCreate(PETSC_COMM_WORLD, 1.0, 1, &dom));
  PetscCall(FluidCreate(&dom, &fl));
  PetscCall(FluidSetFromOptions(fl));
  PetscCall(FluidSetVessel(fl, Cylinder, NULL));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = FluidSetUp(fl);
  PetscCall(PetscPopErrorHandler());
  PetscCall(CheckTrue("patch_vessel_closes_the_outlet_refused", (PetscBool)(ierr == PETSC_ERR_ARG_INCOMP), ierr == PETSC_ERR_ARG_INCOMP ? "FluidSetUp stops: the vessel closes the outlet" : "FluidSetUp did not stop"));
  PetscCall(FluidDestroy(&fl));
  PetscCall(DomainDestroy(&dom));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(CaseA(""));
  PetscCall(CaseA("-fluid_viscous implicit"));
  PetscCall(CaseB());
  PetscCall(CaseFlat());
  PetscCall(CaseStrip("", 1));
  PetscCall(CaseStrip(",0,180", 0.5));
  PetscCall(CaseC());
  PetscCall(CaseD(""));
  PetscCall(CaseD("-fluid_viscous implicit"));
  PetscCall(CaseE());
  PetscCall(PetscFinalize());
  return check_failures ? 1 : 0;
}
