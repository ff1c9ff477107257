/* The XDMF index of a run's frames (see io.h): one temporal collection per kind, a Polyvertex
 * grid per output time for the particles (a time without particles repeats the latest), a Triangle grid for the surface (when written), a
 * 3DCoRectMesh for the fluid, each pointing into the frame files, and an Information element
 * "run_id" (the run's identity, as in every frame file). Rank 0 rewrites it after every
 * frame, under a temporary name renamed into place. */
#include "io/io_private.h"
#include <errno.h>
#include <stdarg.h>
#include <unistd.h>

/* The XDMF index is written through this: the first failed write keeps its errno, and later
 * writes are skipped. */
typedef struct {
  FILE *fp;
  int   err;
} IoText;

static void io_printf(IoText *w, const char *fmt, ...)
{
  va_list ap;

  if (w->err) return;
  va_start(ap, fmt);
  if (vfprintf(w->fp, fmt, ap) < 0) w->err = errno ? errno : EIO;
  va_end(ap);
}

static void IoXdmfAttribute(IoText *w, const IoFrame *fr, const char *group, const IoSet *s, const char *center, const char *dims)
{
  const char *type = s->ncomp == 3 ? "Vector" : (s->ncomp == 1 ? "Scalar" : "Matrix");
  const int   prec = s->isint || fr->prec != 4 ? 8 : 4;
  io_printf(w, "        <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"%s\">\n", s->name, type, center);
  if (s->ncomp > 1) io_printf(w, "          <DataItem Dimensions=\"%s %" PetscInt_FMT "\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">%s:/%s/%s</DataItem>\n", dims, s->ncomp, s->isint ? "Int" : "Float", prec, fr->file, group, s->name);
  else io_printf(w, "          <DataItem Dimensions=\"%s\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">%s:/%s/%s</DataItem>\n", dims, s->isint ? "Int" : "Float", prec, fr->file, group, s->name);
  io_printf(w, "        </Attribute>\n");
}

/* One frame's grid of one kind (0 particles, 1 surface, 2 fluid), at time t. Counts are
 * printed in 64 bits. */
static void IoXdmfGrid(Io io, IoText *w, const IoFrame *fr, int kind, PetscReal t)
{
  char d[96];

  if (kind == 0) {
    snprintf(d, sizeof d, "%lld", fr->np);
    io_printf(w, "      <Grid Name=\"particles\" GridType=\"Uniform\">\n        <Time Value=\"%.17g\"/>\n", (double)t);
    io_printf(w, "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%lld\" NodesPerElement=\"1\">\n          <DataItem Dimensions=\"%lld\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">%s:/particles/vertex</DataItem>\n        </Topology>\n", fr->np, fr->np, fr->file);
    io_printf(w, "        <Geometry GeometryType=\"XYZ\">\n          <DataItem Dimensions=\"%lld 3\" NumberType=\"Float\" Precision=\"%d\" Format=\"HDF\">%s:/particles/position</DataItem>\n        </Geometry>\n", fr->np, fr->prec == 4 ? 4 : 8, fr->file);
    for (PetscInt i = 0; i < fr->npart; i++)
      if (strcmp(fr->part[i].name, "position")) IoXdmfAttribute(w, fr, "particles", &fr->part[i], "Node", d);
  } else if (kind == 1) {
    io_printf(w, "      <Grid Name=\"surface\" GridType=\"Uniform\">\n        <Time Value=\"%.17g\"/>\n", (double)t);
    io_printf(w, "        <Topology TopologyType=\"Triangle\" NumberOfElements=\"%lld\">\n          <DataItem Dimensions=\"%lld 3\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">%s:/surface/triangles</DataItem>\n        </Topology>\n", fr->nsurft, fr->nsurft, fr->file);
    io_printf(w, "        <Geometry GeometryType=\"XYZ\">\n          <DataItem Dimensions=\"%lld 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/surface/points</DataItem>\n        </Geometry>\n", fr->nsurfp, fr->file);
    io_printf(w, "        <Attribute Name=\"id\" AttributeType=\"Scalar\" Center=\"Node\">\n          <DataItem Dimensions=\"%lld\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">%s:/surface/tag</DataItem>\n        </Attribute>\n", fr->nsurfp, fr->file);
  } else {
    snprintf(d, sizeof d, "%" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT, io->fcells[2], io->fcells[1], io->fcells[0]);
    io_printf(w, "      <Grid Name=\"fluid\" GridType=\"Uniform\">\n        <Time Value=\"%.17g\"/>\n", (double)t);
    io_printf(w, "        <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"%lld %lld %lld\"/>\n", (long long)io->fcells[2] + 1, (long long)io->fcells[1] + 1, (long long)io->fcells[0] + 1);
    io_printf(w, "        <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n");
    io_printf(w, "          <DataItem Dimensions=\"3\" Format=\"XML\">%.17g %.17g %.17g</DataItem>\n", (double)io->flo[2], (double)io->flo[1], (double)io->flo[0]);
    io_printf(w, "          <DataItem Dimensions=\"3\" Format=\"XML\">%.17g %.17g %.17g</DataItem>\n        </Geometry>\n", (double)io->fh[2], (double)io->fh[1], (double)io->fh[0]);
    for (PetscInt i = 0; i < fr->nfluid; i++) IoXdmfAttribute(w, fr, "fluid", &fr->fluid[i], "Cell", d);
  }
  io_printf(w, "      </Grid>\n");
}

/* Whether frame fr holds a grid of kind k (0 particles, 1 surface, 2 fluid). */
static PetscBool io_xdmf_has(const IoFrame *fr, int k)
{
  return (PetscBool)(k == 0 ? fr->npart > 0 : (k == 1 ? fr->nsurft > 0 : fr->nfluid > 0));
}

/* Rank 0. The index: one temporal collection per kind (particles, surface, fluid) directly in the
 * domain, so that ParaView's XDMF reader keeps one block of a fixed name ("particles", ...)
 * through time (a spatial collection per frame gave particles[1], particles[2], ... and broke
 * Extract Block after the first frame). Every collection lists every frame's time from its kind's
 * first frame on: at a time whose frame lacks the kind (-io_particle_interval and
 * -io_fluid_interval differ, or -io_fields), the grid of its latest earlier frame repeats, so the
 * legacy reader sees one sorted list of times and every block at each (it took the times of the
 * collections one after another, unsorted, and gave no particles block at a fluid-only time).
 * Written to <index>.tmp, renamed into place; *err is the errno of the first failure (0: none),
 * after which the temporary is removed. */
PetscErrorCode IoWriteIndex(Io io, int *err)
{
  const char *kinds[3] = {"particles", "surface", "fluid"};
  char        tmp[PETSC_MAX_PATH_LEN];
  IoText      w = {NULL, 0};

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(tmp, sizeof tmp, "%s.tmp", io->index));
  *err = 0;
  SableTempSet(tmp);
  w.fp = fopen(tmp, "w");
  if (!w.fp) {
    *err = errno;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  io_printf(&w, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n");
  io_printf(&w, "    <Information Name=\"run_id\" Value=\"%llu\"/>\n", io->run_id);
  for (int k = 0; k < 3; k++) {
    const IoFrame *last = NULL; /* the latest frame holding this kind */
    PetscInt       n    = 0;
    for (PetscInt i = 0; i < io->nframes; i++) n += io_xdmf_has(&io->frames[i], k);
    if (!n) continue;
    io_printf(&w, "    <Grid Name=\"%s\" GridType=\"Collection\" CollectionType=\"Temporal\">\n", kinds[k]);
    for (PetscInt i = 0; i < io->nframes; i++) {
      if (io_xdmf_has(&io->frames[i], k)) last = &io->frames[i];
      if (last) IoXdmfGrid(io, &w, last, k, io->frames[i].t);
    }
    io_printf(&w, "    </Grid>\n");
  }
  io_printf(&w, "  </Domain>\n</Xdmf>\n");
  if (fflush(w.fp) != 0 && !w.err) w.err = errno; /* the buffered tail: where a full disk shows */
  if (fclose(w.fp) != 0 && !w.err) w.err = errno;
  if (!w.err && rename(tmp, io->index) != 0) w.err = errno;
  if (w.err) unlink(tmp);
  *err = w.err;
  PetscFunctionReturn(PETSC_SUCCESS);
}
