/* What the drivers put in the monitor file (io/monitor.c), one row every -mon_interval:
 *   time [s]; step [-] (DEM steps; a coupled run's fluid steps); particles [-];
 *   kinetic_energy, rotational_energy [J]; max_overlap [radius]; contacts, wall_contacts [-];
 *   bed_height_95 [m] (the centre height below which 95% of the solids mass lies, along
 *   gravity), mean_height [m] (the centre of mass along gravity);
 *   inserted, removed [-] and inserted_mass, removed_mass [kg]: the particles sources added and
 *   outlets took since the start (particles = initial + inserted - removed);
 *   box<k>_mass [kg], box<k>_count [-] for each -mon_box_<k> lo_x,lo_y,lo_z,hi_x,hi_y,hi_z;
 *   a coupled run adds p_probe<k> [Pa] at each -mon_probe_<k> x,y,z (the cell-centred pressure
 *   interpolated trilinearly), dp<k> [Pa] = p(probe a) - p(probe b) for each -mon_dp_<k> a,b,
 *   eps_min [-], poisson_iterations [-] (of the last fluid step);
 *   wall_time [s] since the loop started and wall_time_per_step [s] over the last interval.
 * Every figure is one a user can compute again from a frame at the same time. */
#include "drivers/drivers.h"

#define DRIVER_MON_MAX 8

PetscErrorCode DriverMonSetFromOptions(DriverMon *m, MPI_Comm comm, PetscBool coupled)
{
  char      opt[64];
  PetscReal v[6];
  PetscBool set;

  PetscFunctionBeginUser;
  m->comm    = comm;
  m->coupled = coupled;
  PetscCall(MonCreate(comm, &m->mon));
  PetscCall(MonSetFromOptions(m->mon));
  PetscOptionsBegin(comm, NULL, "Monitor contents", NULL);
  for (int k = 0; k < DRIVER_MON_MAX; k++) {
    PetscCall(PetscSNPrintf(opt, sizeof opt, "-mon_box_%d", k));
    PetscCall(SableOptionsRealN(opt, "A box whose solids mass and particle count the monitor reports: lo_x,lo_y,lo_z,hi_x,hi_y,hi_z", "m", v, 0, 6, &set));
    if (!set) continue;
    PetscCheck(v[0] < v[3] && v[1] < v[4] && v[2] < v[5], comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g,%g,%g,%g,%g,%g: need lo < hi on every axis (m)", opt, (double)v[0], (double)v[1], (double)v[2], (double)v[3], (double)v[4], (double)v[5]);
    m->boxid[m->nbox] = k;
    PetscCall(PetscArraycpy(m->box[m->nbox++], v, 6));
  }
  { /* read in every run (-help lists them once); a dry run has no fluid to probe */
    for (int k = 0; k < DRIVER_MON_MAX; k++) {
      PetscCall(PetscSNPrintf(opt, sizeof opt, "-mon_probe_%d", k));
      PetscCall(SableOptionsRealN(opt, "A point whose fluid pressure the monitor reports (coupled runs): x,y,z", "m", v, 0, 3, &set));
      PetscCheck(!set || coupled, comm, PETSC_ERR_ARG_INCOMP, "%s: a probe of the fluid pressure; this run is dry (no -fluid_ or -cpl_ options)", opt);
      m->probe_set[k] = set;
      if (set) PetscCall(PetscArraycpy(m->probe[k], v, 3));
    }
    for (int k = 0; k < DRIVER_MON_MAX; k++) {
      PetscInt ab[2];
      PetscCall(PetscSNPrintf(opt, sizeof opt, "-mon_dp_%d", k));
      PetscCall(PetscOptionsIntArray(opt, "Pressure drop the monitor reports: p(probe a) - p(probe b), probes of -mon_probe_<a>, -mon_probe_<b>", NULL, ab, &(PetscInt){2}, &set));
      if (!set) continue;
      PetscCheck(ab[0] >= 0 && ab[0] < DRIVER_MON_MAX && ab[1] >= 0 && ab[1] < DRIVER_MON_MAX && m->probe_set[ab[0]] && m->probe_set[ab[1]], comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %d,%d: both must be probes given by -mon_probe_<k> (k in [0,%d])", opt, (int)ab[0], (int)ab[1], DRIVER_MON_MAX - 1);
      m->dpid[m->ndp]    = k;
      m->dp[m->ndp][0]   = ab[0];
      m->dp[m->ndp++][1] = ab[1];
    }
  }
  PetscOptionsEnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The columns, in the order DriverMonRow fills them. */
static PetscErrorCode DriverMonColumns(DriverMon *m)
{
  const char *dem[][2] = {{"time", "s"}, {"step", "-"}, {"particles", "-"}, {"kinetic_energy", "J"}, {"rotational_energy", "J"}, {"max_overlap", "radius"}, {"contacts", "-"}, {"wall_contacts", "-"}, {"bed_height_95", "m"}, {"mean_height", "m"}, {"inserted", "-"}, {"removed", "-"}, {"inserted_mass", "kg"}, {"removed_mass", "kg"}};
  char        name[64];

  PetscFunctionBeginUser;
  for (size_t c = 0; c < sizeof dem / sizeof dem[0]; c++) PetscCall(MonAddColumn(m->mon, dem[c][0], dem[c][1]));
  for (PetscInt b = 0; b < m->nbox; b++) {
    PetscCall(PetscSNPrintf(name, sizeof name, "box%d_mass", (int)m->boxid[b]));
    PetscCall(MonAddColumn(m->mon, name, "kg"));
    PetscCall(PetscSNPrintf(name, sizeof name, "box%d_count", (int)m->boxid[b]));
    PetscCall(MonAddColumn(m->mon, name, "-"));
  }
  if (m->coupled) {
    for (int k = 0; k < DRIVER_MON_MAX; k++) {
      if (!m->probe_set[k]) continue;
      PetscCall(PetscSNPrintf(name, sizeof name, "p_probe%d", k));
      PetscCall(MonAddColumn(m->mon, name, "Pa"));
    }
    for (PetscInt d = 0; d < m->ndp; d++) {
      PetscCall(PetscSNPrintf(name, sizeof name, "dp%d", (int)m->dpid[d]));
      PetscCall(MonAddColumn(m->mon, name, "Pa"));
    }
    PetscCall(MonAddColumn(m->mon, "eps_min", "-"));
    PetscCall(MonAddColumn(m->mon, "poisson_iterations", "-"));
  }
  PetscCall(MonAddColumn(m->mon, "wall_time", "s"));
  PetscCall(MonAddColumn(m->mon, "wall_time_per_step", "s"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DriverMonSetUp(DriverMon *m, Io io)
{
  PetscBool on;

  PetscFunctionBeginUser;
  PetscCall(MonSetUp(m->mon, io));
  PetscCall(MonIsActive(m->mon, &on));
  if (on) PetscCall(DriverMonColumns(m));
  m->ready = on;
  PetscCall(PetscTime(&m->wall0));
  m->wall_last = m->wall0;
  m->step_last = -1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DriverMonRow(DriverMon *m, const DriverMonInput *in)
{
  PetscReal      v[128], h, mean;
  PetscInt       c = 0, ncol;
  PetscBool      due;
  DemStats       st;
  DemFlowStats   fl;
  PetscLogDouble now;

  PetscFunctionBeginUser;
  if (!m->ready) PetscFunctionReturn(PETSC_SUCCESS); /* no monitor, or a loop run without DriverMonSetUp */
  PetscCall(MonDue(m->mon, in->t, &due));
  if (!due) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(MonGetColumnCount(m->mon, &ncol));
  PetscCheck(ncol <= (PetscInt)(sizeof v / sizeof v[0]), m->comm, PETSC_ERR_PLIB, "monitor: %d columns", (int)ncol);
  PetscCall(DemGetStats(in->dem, &st));
  PetscCall(DemGetBedHeights(in->dem, 0.95, &h, &mean));
  v[c++] = in->t;
  v[c++] = (PetscReal)in->step;
  v[c++] = (PetscReal)st.n;
  v[c++] = st.ke;
  v[c++] = st.ke_rot;
  v[c++] = st.max_overlap;
  v[c++] = (PetscReal)st.contacts;
  v[c++] = (PetscReal)st.wall_contacts;
  v[c++] = h;
  v[c++] = mean;
  PetscCall(DemGetFlow(in->dem, &fl));
  v[c++] = (PetscReal)fl.inserted;
  v[c++] = (PetscReal)fl.removed;
  v[c++] = fl.m_inserted;
  v[c++] = fl.m_removed;
  for (PetscInt b = 0; b < m->nbox; b++) {
    PetscInt cnt;
    PetscCall(DemGetMassInBox(in->dem, m->box[b], m->box[b] + 3, &v[c], &cnt));
    v[c + 1] = (PetscReal)cnt;
    c += 2;
  }
  if (m->coupled) {
    PetscReal p[DRIVER_MON_MAX] = {0};
    for (int k = 0; k < DRIVER_MON_MAX; k++)
      if (m->probe_set[k]) {
        PetscCall(FluidProbePressure(in->fluid, m->probe[k], &p[k]));
        v[c++] = p[k];
      }
    for (PetscInt d = 0; d < m->ndp; d++) v[c++] = p[m->dp[d][0]] - p[m->dp[d][1]];
    v[c++] = in->cst ? in->cst->eps_min : 1;
    v[c++] = in->cst ? (PetscReal)in->cst->fluid.poisson_its : 0;
  }
  PetscCall(PetscTime(&now));
  v[c++]       = now - m->wall0;
  v[c++]       = m->step_last >= 0 && in->step > m->step_last ? (now - m->wall_last) / (in->step - m->step_last) : 0;
  m->wall_last = now;
  m->step_last = in->step;
  PetscCheck(c == ncol, m->comm, PETSC_ERR_PLIB, "monitor: %d values for %d columns", (int)c, (int)ncol);
  PetscCall(MonWriteRow(m->mon, v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DriverMonDestroy(DriverMon *m)
{
  PetscFunctionBeginUser;
  PetscCall(MonDestroy(&m->mon));
  PetscFunctionReturn(PETSC_SUCCESS);
}
