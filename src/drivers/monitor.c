/* What the drivers put in the monitor file (io/monitor.c), one row every -mon_interval; the
 * columns and their definitions are listed in doc/output.md ("Monitor file"). Each column is one
 * line of DriverMonFill: MonCol(cols, name, index, unit, value) declares the column (name and
 * unit) while the header is made and fills its value in each row, so a column's name, unit and
 * value stay together; each value is placed under the column declared with its name and unit
 * (MonCheckColumn), so the two passes cannot pair a value with another column's name. The indexed families (-mon_box_<k>, -mon_surface_<k>, -mon_flux_<k>, and
 * for coupled runs -mon_probe_<k>, -mon_dp_<k>, -mon_line_<k>, -mon_plane_<k>) take any number
 * of members: the indices given are found in the options database, and their columns follow in
 * increasing index; nothing is computed for a family left empty. The particle figures come from
 * the DEM's getters (dem/monitor.c), the fluid ones from the fluid's (fluid/probe.c): every
 * figure is one a user can compute again from a frame at the same time. All collective. */
#include "drivers/drivers.h"
#include "geom/region.h"
#include <ctype.h>

/* The plane options take words ("z=0.05"); -mon_average_fields is a literal word option. */
static const char *const DriverMonWordOptions[] = {"-mon_flux_%d", "-mon_plane_%d"};

/* The indices k of the options -<family>_<k> given (sorted, without repeats), and always 0 so
 * that -help lists the family; *idx is freed by the caller. Not collective. */
static PetscErrorCode DriverMonIndices(const char *family, PetscInt *n, PetscInt **idx)
{
  char    *all, *tok, *save = NULL;
  size_t   len;
  PetscInt cap = 8;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(cap, idx));
  (*idx)[0] = 0;
  *n        = 1;
  PetscCall(PetscOptionsGetAll(NULL, &all));
  PetscCall(PetscStrlen(family, &len));
  for (tok = strtok_r(all, " ", &save); tok; tok = strtok_r(NULL, " ", &save)) {
    const char *s = tok + 1 + len + 1;
    char       *end;
    long        k;
    if (tok[0] != '-' || strncmp(tok + 1, family, len) || tok[1 + len] != '_' || !isdigit((unsigned char)*s)) continue;
    k = strtol(s, &end, 10);
    if (*end || k > 999999) continue; /* another option of the family (-mon_surface_dz), or an index too long: the unused-option check names it */
    if (*n == cap) PetscCall(PetscRealloc(sizeof(PetscInt) * (cap *= 2), idx));
    (*idx)[(*n)++] = (PetscInt)k;
  }
  PetscCall(PetscFree(all));
  PetscCall(PetscSortRemoveDupsInt(n, *idx));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Appends region r to the list *list of *n (grown one at a time: set-up only). */
static PetscErrorCode DriverMonAppend(DriverMonRegion **list, PetscInt *n, const DriverMonRegion *r)
{
  PetscFunctionBeginUser;
  PetscCall(PetscRealloc(sizeof(DriverMonRegion) * (*n + 1), list));
  (*list)[(*n)++] = *r;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A plane option's value: "x=c", "y=c", "z=c" (a whole cross-section: the rectangle unbounded,
 * clipped to the domain where used) or lo_x,lo_y,lo_z,hi_x,hi_y,hi_z with lo = hi on exactly one
 * axis (a rectangle). */
static PetscErrorCode DriverMonParsePlane(MPI_Comm comm, const char *opt, const char *val, DriverMonRegion *r)
{
  const char *help = "give x=c, y=c or z=c (m: the whole cross-section) or lo_x,lo_y,lo_z,hi_x,hi_y,hi_z (m) with lo = hi on exactly one axis (a rectangle)";
  PetscReal   v[6];
  int         n = 0, flat = 0;
  const char *s = val;
  char       *end;

  PetscFunctionBeginUser;
  if ((val[0] == 'x' || val[0] == 'y' || val[0] == 'z') && val[1] == '=') {
    const PetscReal c = strtod(val + 2, &end);
    PetscCheck(end != val + 2 && !*end && !PetscIsInfOrNanReal(c), comm, PETSC_ERR_ARG_WRONG, "%s %s: %s", opt, val, help);
    r->axis = val[0] - 'x';
    for (int d = 0; d < 3; d++) r->lo[d] = -PETSC_MAX_REAL, r->hi[d] = PETSC_MAX_REAL;
    r->lo[r->axis] = r->hi[r->axis] = c;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  while (n < 6) {
    v[n] = strtod(s, &end);
    if (end == s) break;
    n++;
    s = end;
    if (*s != ',') break;
    s++;
  }
  PetscCheck(n == 6 && !*s, comm, PETSC_ERR_ARG_WRONG, "%s %s: %s", opt, val, help);
  for (int d = 0; d < 3; d++) {
    PetscCheck(v[d] <= v[d + 3], comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %s: lo > hi on axis %c; %s", opt, val, 'x' + d, help);
    if (v[d] == v[d + 3]) flat++, r->axis = d;
    r->lo[d] = v[d];
    r->hi[d] = v[d + 3];
  }
  PetscCheck(flat == 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %s: flat along %d axes; %s", opt, val, flat, help);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The indexed families of a box or segment (six reals) into *list. */
static PetscErrorCode DriverMonReadBoxes(PetscOptionItems *PetscOptionsObject, DriverMon *m, const char *family, const char *pattern, const char *text, PetscBool fluid, PetscBool segment, DriverMonRegion **list, PetscInt *n)
{
  PetscInt *idx, ni;
  char      opt[64];

  PetscFunctionBeginUser;
  PetscCall(DriverMonIndices(family, &ni, &idx));
  for (PetscInt i = 0; i < ni; i++) {
    DriverMonRegion r = {.k = idx[i]};
    GeomRegion      box;
    PetscReal      *v = box.g; /* a box region's lo, hi (geom/region.h), or a segment's ends */
    PetscBool       set;
    PetscCall(PetscSNPrintf(opt, sizeof opt, pattern, (int)idx[i]));
    if (segment) PetscCall(SableOptionsRealN(opt, text, "m", v, 0, 6, &set));
    else PetscCall(GeomRegionOption(opt, GEOM_REGION_BOX, text, &box, &set));
    if (!set) continue;
    PetscCheck(!fluid || m->coupled, m->comm, PETSC_ERR_ARG_INCOMP, "%s: an average of the fluid's fields; this run is dry (a coupled run has -fluid_ or -cpl_ options, or -sable_solver coupled)", opt);
    if (segment) PetscCheck(v[0] != v[3] || v[1] != v[4] || v[2] != v[5], m->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g,%g,%g,%g,%g,%g: the two ends coincide (m)", opt, (double)v[0], (double)v[1], (double)v[2], (double)v[3], (double)v[4], (double)v[5]);
    for (int d = 0; d < 3; d++) r.lo[d] = v[d], r.hi[d] = v[d + 3];
    PetscCall(PetscStrncpy(r.name, opt, sizeof r.name));
    PetscCall(DriverMonAppend(list, n, &r));
  }
  PetscCall(PetscFree(idx));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The indexed families of a plane (DriverMonParsePlane) into *list. */
static PetscErrorCode DriverMonReadPlanes(PetscOptionItems *PetscOptionsObject, DriverMon *m, const char *family, const char *pattern, const char *text, PetscBool fluid, DriverMonRegion **list, PetscInt *n)
{
  PetscInt *idx, ni;
  char      opt[64], val[256];

  PetscFunctionBeginUser;
  PetscCall(DriverMonIndices(family, &ni, &idx));
  for (PetscInt i = 0; i < ni; i++) {
    DriverMonRegion r = {.k = idx[i]};
    PetscBool       set;
    val[0] = 0;
    PetscCall(PetscSNPrintf(opt, sizeof opt, pattern, (int)idx[i]));
    PetscCall(SableOptionsString(opt, text, val, sizeof val, &set));
    if (!set) continue;
    PetscCheck(!fluid || m->coupled, m->comm, PETSC_ERR_ARG_INCOMP, "%s: an average of the fluid's fields; this run is dry (a coupled run has -fluid_ or -cpl_ options, or -sable_solver coupled)", opt);
    PetscCall(DriverMonParsePlane(m->comm, opt, val, &r));
    PetscCall(PetscStrncpy(r.name, opt, sizeof r.name));
    PetscCall(DriverMonAppend(list, n, &r));
  }
  PetscCall(PetscFree(idx));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Point probes and the pressure drops between them (coupled runs). */
static PetscErrorCode DriverMonReadProbes(PetscOptionItems *PetscOptionsObject, DriverMon *m)
{
  PetscInt *idx, ni;
  char      opt[64];
  PetscBool help; /* -help lists the options: a pair naming probes not given is no error there */

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  PetscCall(DriverMonIndices("mon_probe", &ni, &idx));
  for (PetscInt i = 0; i < ni; i++) {
    DriverMonRegion r = {.k = idx[i]};
    PetscBool       set;
    PetscCall(PetscSNPrintf(opt, sizeof opt, "-mon_probe_%d", (int)idx[i]));
    PetscCall(SableOptionsRealN(opt, "A point whose fluid pressure the monitor reports (coupled runs): x,y,z; any k >= 0", "m", r.lo, 0, 3, &set));
    PetscCheck(!set || m->coupled, m->comm, PETSC_ERR_ARG_INCOMP, "%s: a probe of the fluid pressure; this run is dry (a coupled run has -fluid_ or -cpl_ options, or -sable_solver coupled)", opt);
    if (set) PetscCall(DriverMonAppend(&m->probe, &m->nprobe, &r));
  }
  PetscCall(PetscFree(idx));
  PetscCall(DriverMonIndices("mon_dp", &ni, &idx));
  for (PetscInt i = 0; i < ni; i++) {
    DriverMonRegion r     = {.k = idx[i]};
    PetscInt        ab[2] = {0, 0}, at[2] = {-1, -1};
    PetscBool       set;
    PetscCall(PetscSNPrintf(opt, sizeof opt, "-mon_dp_%d", (int)idx[i]));
    PetscCall(SableOptionsIntN(opt, "Pressure drop the monitor reports: p(probe a) - p(probe b), probes of -mon_probe_<a>, -mon_probe_<b>; any k >= 0", NULL, "[0,inf)", ab, 0, 2, &set));
    if (!set) continue;
    for (PetscInt p = 0; p < m->nprobe; p++)
      for (int e = 0; e < 2; e++)
        if (m->probe[p].k == ab[e]) at[e] = p;
    PetscCheck((at[0] >= 0 && at[1] >= 0) || help, m->comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %d,%d: both must be probes given by -mon_probe_<k>", opt, (int)ab[0], (int)ab[1]);
    r.ab[0] = at[0];
    r.ab[1] = at[1];
    PetscCall(DriverMonAppend(&m->dp, &m->ndp, &r));
  }
  PetscCall(PetscFree(idx));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DriverMonSetFromOptions(DriverMon *m, MPI_Comm comm, PetscBool coupled)
{
  char     *fp[8]; /* room past the three fields: a longer list is refused, not cut */
  PetscInt  nf = 8;
  PetscBool set;

  PetscFunctionBeginUser;
  m->comm    = comm;
  m->coupled = coupled;
  PetscCall(MonCreate(comm, &m->mon));
  PetscCall(MonSetFromOptions(m->mon));
  PetscOptionsBegin(comm, NULL, "Monitor contents", NULL);
  PetscCall(DriverMonReadBoxes(PetscOptionsObject, m, "mon_box", "-mon_box_%d", "A box whose solids mass and particle count the monitor reports: lo_x,lo_y,lo_z,hi_x,hi_y,hi_z; any k >= 0", PETSC_FALSE, PETSC_FALSE, &m->box, &m->nbox));
  PetscCall(DriverMonReadBoxes(PetscOptionsObject, m, "mon_surface", "-mon_surface_%d", "A box whose bed surface the monitor reports (the particles with centres in it; slabs along gravity): lo_x,lo_y,lo_z,hi_x,hi_y,hi_z; any k >= 0", PETSC_FALSE, PETSC_FALSE, &m->surf, &m->nsurf));
  PetscCall(SableOptionsReal("-mon_surface_dz", "Thickness of the slabs of the bed surfaces' solids profile; default 2 x the largest particle diameter", "m", "(0,inf)", 0, &m->surf_dz, NULL));
  PetscCall(SableOptionsReal("-mon_surface_fraction", "A bed surface is where the solids profile, read from the top, first reaches this fraction of its densest slab", NULL, "(0,1]", 0.5, &m->surf_frac, NULL));
  PetscCall(DriverMonReadPlanes(PetscOptionsObject, m, "mon_flux", DriverMonWordOptions[0], "A plane through which the monitor reports the solids mass flow (kg/s, along +axis): x=c, y=c, z=c (whole), or a rectangle lo_x,lo_y,lo_z,hi_x,hi_y,hi_z flat along one axis; any k >= 0", PETSC_FALSE, &m->flux, &m->nflux));
  PetscCall(SableOptionsReal("-mon_flux_width", "Width of the slab about a -mon_flux_<k> plane whose particles count: flow = sum(m v.n) / width; default 2 x the largest particle diameter", "m", "(0,inf)", 0, &m->flux_width, NULL));
  PetscCall(DriverMonReadProbes(PetscOptionsObject, m));
  if (coupled) PetscCall(FluidPatchIndices(&m->npatch, &m->patch)); /* as the fluid numbers its patches */
  PetscCall(DriverMonReadBoxes(PetscOptionsObject, m, "mon_line", "-mon_line_%d", "A segment along which the monitor averages the fluid's fields (coupled runs): x0,y0,z0,x1,y1,z1; any k >= 0", PETSC_TRUE, PETSC_TRUE, &m->line, &m->nline));
  PetscCall(DriverMonReadPlanes(PetscOptionsObject, m, "mon_plane", DriverMonWordOptions[1], "A plane over which the monitor averages the fluid's fields (coupled runs): x=c, y=c, z=c (whole), or a rectangle lo_x,lo_y,lo_z,hi_x,hi_y,hi_z flat along one axis; any k >= 0", PETSC_TRUE, &m->plane, &m->nplane));
  PetscCall(PetscOptionsStringArray("-mon_average_fields", "Fields the -mon_line_<k> and -mon_plane_<k> averages report: p (Pa), eps (-), u (interstitial velocity, 3 columns, m/s); default p,eps,u", NULL, fp, &nf, &set));
  PetscCheck(!set || (nf >= 1 && nf <= 3), comm, PETSC_ERR_ARG_OUTOFRANGE, "-mon_average_fields: %d items; give 1 to 3 of p, eps, u", (int)nf);
  for (int q = 0; q < 3; q++) m->fields[q] = (PetscBool)!set;
  for (PetscInt q = 0; set && q < nf; q++) {
    PetscBool p, e, u;
    PetscCall(PetscStrcmp(fp[q], "p", &p));
    PetscCall(PetscStrcmp(fp[q], "eps", &e));
    PetscCall(PetscStrcmp(fp[q], "u", &u));
    PetscCheck(p || e || u, comm, PETSC_ERR_ARG_OUTOFRANGE, "-mon_average_fields: %s is not one of p, eps, u", fp[q]);
    m->fields[p ? 0 : e ? 1
                        : 2] = PETSC_TRUE;
  }
  for (PetscInt q = 0; set && q < nf; q++) PetscCall(PetscFree(fp[q])); /* PetscOptionsStringArray allocates the strings */
  PetscCheck(!set || coupled, comm, PETSC_ERR_ARG_INCOMP, "-mon_average_fields: the fields of -mon_line_<k> and -mon_plane_<k> averages; this run is dry (a coupled run has -fluid_ or -cpl_ options, or -sable_solver coupled)");
  PetscOptionsEnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Declaring the columns (declare) or filling a row's values (row). */
typedef struct {
  Mon        mon;
  PetscBool  declare;
  PetscReal *row;
  PetscInt   c, ncol;
} MonCols;

/* One column: its name (a printf pattern of the index k when it has one), unit and value. Each
 * value is placed under the column declared with the same name and unit (MonCheckColumn), not
 * merely at the same position, so a column the two passes take differently stops the run. */
static PetscErrorCode MonCol(MonCols *cols, const char *name, PetscInt k, const char *unit, PetscReal v)
{
  char buf[64];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(buf, sizeof buf, name, (int)k));
  if (cols->declare) PetscCall(MonAddColumn(cols->mon, buf, unit));
  else {
    PetscCall(MonCheckColumn(cols->mon, cols->c, buf, unit));
    cols->row[cols->c] = v;
  }
  cols->c++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The fluid's columns: probes, pressure drops, line and plane averages (coupled runs). */
static PetscErrorCode DriverMonFillFluid(DriverMon *m, MonCols *cols, const DriverMonInput *in)
{
  const struct {
    const char *name, *unit; /* the name a printf pattern of the family (line, plane) and index */
  } fcol[5]    = {{"%s%d_p", "Pa"}, {"%s%d_eps", "-"}, {"%s%d_ux", "m/s"}, {"%s%d_uy", "m/s"}, {"%s%d_uz", "m/s"}};
  PetscReal *p = NULL, *avg = NULL, emin = 1;
  PetscInt   nspan = m->nline + m->nplane;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc2(m->nprobe, &p, 5 * nspan, &avg));
  if (!cols->declare) {
    for (PetscInt i = 0; i < m->nprobe; i++) PetscCall(FluidProbePressure(in->fluid, m->probe[i].lo, &p[i]));
    if (nspan) PetscCall(FluidAverageFields(in->fluid, nspan, m->spans, m->fields[2], avg));
  }
  for (PetscInt i = 0; i < m->nprobe; i++) PetscCall(MonCol(cols, "p_probe%d", m->probe[i].k, "Pa", p[i]));
  for (PetscInt d = 0; d < m->ndp; d++) PetscCall(MonCol(cols, "dp%d", m->dp[d].k, "Pa", p[m->dp[d].ab[0]] - p[m->dp[d].ab[1]]));
  for (PetscInt s = 0; s < nspan; s++)
    for (int q = 0; q < 5; q++) {
      const PetscBool line = (PetscBool)(s < m->nline);
      char            name[32];
      if (!m->fields[q < 2 ? q : 2]) continue;
      PetscCall(PetscSNPrintf(name, sizeof name, fcol[q].name, line ? "line" : "plane", (int)(line ? m->line[s].k : m->plane[s - m->nline].k)));
      PetscCall(MonCol(cols, name, 0, fcol[q].unit, avg[5 * s + q]));
    }
  PetscCall(PetscFree2(p, avg));
  for (PetscInt i = 0; i < m->npatch; i++) { /* the fluid's patches: mean pressure, mass flow from the face fluxes */
    PetscReal pp = 0, mdot = 0;
    PetscInt  k = m->patch[i];
    if (!cols->declare) PetscCall(FluidPatchMeasure(in->fluid, i, &k, &pp, &mdot));
    PetscCheck(k == m->patch[i], m->comm, PETSC_ERR_PLIB, "monitor: fluid patch %d is -fluid_patch_%d, expected %d", (int)i, (int)k, (int)m->patch[i]);
    PetscCall(MonCol(cols, "patch%d_p", k, "Pa", pp));
    PetscCall(MonCol(cols, "patch%d_mdot", k, "kg/s", mdot));
  }
  if (!cols->declare && !in->cst) { /* before the first coupling step (a run's start, a restart's first row): the porosity set up */
    Vec eps;
    PetscCall(FluidGetPorosity(in->fluid, &eps));
    PetscCall(VecMin(eps, NULL, &emin));
  }
  PetscCall(MonCol(cols, "eps_min", 0, "-", in->cst ? in->cst->eps_min : emin));
  PetscCall(MonCol(cols, "poisson_iterations", 0, "-", in->cst ? (PetscReal)in->cst->fluid.poisson_its : 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Every column, in order; values only when !cols->declare (then in is the row's input). */
static PetscErrorCode DriverMonFill(DriverMon *m, MonCols *cols, const DriverMonInput *in)
{
  const PetscBool get   = (PetscBool)!cols->declare;
  const PetscReal lo[3] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL}, hi[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}; /* the domain */
  DemStats        st  = {0};
  DemFlowStats    fl  = {0};
  PetscReal       h95 = 0, mean = 0, surf = 0, top = 0, v = 0;
  PetscInt        cnt = 0;
  PetscLogDouble  now = 0;

  PetscFunctionBeginUser;
  if (get) {
    PetscCall(DemGetStats(in->dem, &st));
    PetscCall(DemGetBedHeights(in->dem, 0.95, &h95, &mean));
    PetscCall(DemGetFlow(in->dem, &fl));
    PetscCall(DemGetBedSurface(in->dem, lo, hi, m->surf_dz, m->surf_frac, &surf));
    PetscCall(DemGetHighest(in->dem, &top));
  }
  PetscCall(MonCol(cols, "time", 0, "s", in->t));
  PetscCall(MonCol(cols, "step", 0, "-", (PetscReal)in->step));
  PetscCall(MonCol(cols, "particles", 0, "-", (PetscReal)st.n));
  PetscCall(MonCol(cols, "kinetic_energy", 0, "J", st.ke));
  PetscCall(MonCol(cols, "rotational_energy", 0, "J", st.ke_rot));
  PetscCall(MonCol(cols, "max_overlap", 0, "radius", st.max_overlap));
  PetscCall(MonCol(cols, "contacts", 0, "-", (PetscReal)st.contacts));
  PetscCall(MonCol(cols, "wall_contacts", 0, "-", (PetscReal)st.wall_contacts));
  PetscCall(MonCol(cols, "bed_height_95", 0, "m", h95));
  PetscCall(MonCol(cols, "mean_height", 0, "m", mean));
  PetscCall(MonCol(cols, "inserted", 0, "-", (PetscReal)fl.inserted));
  PetscCall(MonCol(cols, "removed", 0, "-", (PetscReal)fl.removed));
  PetscCall(MonCol(cols, "inserted_mass", 0, "kg", fl.m_inserted));
  PetscCall(MonCol(cols, "removed_mass", 0, "kg", fl.m_removed));
  PetscCall(MonCol(cols, "bed_surface", 0, "m", surf));
  PetscCall(MonCol(cols, "highest_particle", 0, "m", top));
  for (PetscInt b = 0; b < m->nbox; b++) {
    if (get) PetscCall(DemGetMassInBox(in->dem, m->box[b].lo, m->box[b].hi, &v, &cnt));
    PetscCall(MonCol(cols, "box%d_mass", m->box[b].k, "kg", v));
    PetscCall(MonCol(cols, "box%d_count", m->box[b].k, "-", (PetscReal)cnt));
  }
  for (PetscInt s = 0; s < m->nsurf; s++) {
    if (get) PetscCall(DemGetBedSurface(in->dem, m->surf[s].lo, m->surf[s].hi, m->surf_dz, m->surf_frac, &v));
    PetscCall(MonCol(cols, "surface%d", m->surf[s].k, "m", v));
  }
  for (PetscInt f = 0; f < m->nflux; f++) {
    if (get) PetscCall(DemGetMassFlow(in->dem, m->flux[f].lo, m->flux[f].hi, m->flux[f].axis, m->flux_width, &v));
    PetscCall(MonCol(cols, "flux%d", m->flux[f].k, "kg/s", v));
  }
  if (m->coupled) PetscCall(DriverMonFillFluid(m, cols, in));
  if (get) PetscCall(PetscTime(&now));
  PetscCall(MonCol(cols, "wall_time", 0, "s", now - m->wall0));
  PetscCall(MonCol(cols, "wall_time_per_step", 0, "s", m->step_last >= 0 && in->step > m->step_last ? (now - m->wall_last) / (in->step - m->step_last) : 0));
  if (get) {
    m->wall_last = now;
    m->step_last = in->step;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscLogEvent DRIVER_MonRow = -1;

PetscErrorCode DriverMonSetUp(DriverMon *m, Io io)
{
  PetscBool on;

  PetscFunctionBeginUser;
  if (DRIVER_MonRow < 0) { /* -log_view shows the monitor's time as DriverMonRow */
    PetscClassId cid;
    PetscCall(PetscClassIdRegister("Drivers", &cid));
    PetscCall(PetscLogEventRegister("DriverMonRow", cid, &DRIVER_MonRow));
  }
  PetscCall(MonSetUp(m->mon, io));
  PetscCall(MonIsActive(m->mon, &on));
  if (on) {
    MonCols        cols = {m->mon, PETSC_TRUE, NULL, 0, 0};
    DriverMonInput in   = {0, 0, NULL, NULL, NULL};
    PetscCall(DriverMonFill(m, &cols, &in));
    PetscCall(MonGetColumnCount(m->mon, &m->ncol));
    PetscCall(PetscMalloc1(m->ncol, &m->row));
    PetscCall(PetscMalloc1(m->nline + m->nplane, &m->spans));
    for (PetscInt s = 0; s < m->nline + m->nplane; s++) {
      const DriverMonRegion *r = s < m->nline ? &m->line[s] : &m->plane[s - m->nline];
      m->spans[s].line         = (PetscBool)(s < m->nline);
      m->spans[s].name         = r->name;
      for (int d = 0; d < 3; d++) m->spans[s].a[d] = r->lo[d], m->spans[s].b[d] = r->hi[d];
    }
  }
  m->ready = on;
  PetscCall(PetscTime(&m->wall0));
  m->wall_last = m->wall0;
  m->step_last = -1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DriverMonRow(DriverMon *m, const DriverMonInput *in)
{
  PetscBool due;
  MonCols   cols = {m->mon, PETSC_FALSE, m->row, 0, m->ncol};

  PetscFunctionBeginUser;
  if (!m->ready) PetscFunctionReturn(PETSC_SUCCESS); /* no monitor, or a loop run without DriverMonSetUp */
  PetscCall(MonDue(m->mon, in->t, &due));
  if (!due) PetscFunctionReturn(PETSC_SUCCESS);
  if (m->surf_dz <= 0 || m->flux_width <= 0) { /* the defaults: two diameters of the largest particle */
    PetscReal r;
    PetscCall(DemGetLargestRadius(in->dem, &r));
    if (m->surf_dz <= 0) m->surf_dz = 4 * r;
    if (m->flux_width <= 0) m->flux_width = 4 * r;
  }
  PetscCall(PetscLogEventBegin(DRIVER_MonRow, 0, 0, 0, 0));
  PetscCall(DriverMonFill(m, &cols, in));
  PetscCheck(cols.c == m->ncol, m->comm, PETSC_ERR_PLIB, "monitor: %d values for %d columns", (int)cols.c, (int)m->ncol);
  PetscCall(MonWriteRow(m->mon, m->row));
  PetscCall(PetscLogEventEnd(DRIVER_MonRow, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DriverMonDestroy(DriverMon *m)
{
  PetscFunctionBeginUser;
  PetscCall(MonDestroy(&m->mon));
  PetscCall(PetscFree(m->box));
  PetscCall(PetscFree(m->surf));
  PetscCall(PetscFree(m->flux));
  PetscCall(PetscFree(m->probe));
  PetscCall(PetscFree(m->dp));
  PetscCall(PetscFree(m->line));
  PetscCall(PetscFree(m->plane));
  PetscCall(PetscFree(m->spans));
  PetscCall(PetscFree(m->row));
  PetscCall(PetscFree(m->patch));
  PetscFunctionReturn(PETSC_SUCCESS);
}
