/* STL reader and the life cycle of a TriMesh (the interface is geom/trimesh.h).
 *
 * Rank 0 reads the whole file, decides its form from the content and parses it into a local
 * soup; the status, the error line and the triangles are then broadcast, so every rank gets
 * the same mesh or stops with the same one-line error (never a hang). The form: a file of
 * 84 + 50 n bytes, n the little-endian count at byte 80, is binary (even when its header
 * begins with "solid", as many CAD exports do); any other file without a NUL byte is ASCII
 * ("solid", then "facet normal nx ny nz / outer loop / vertex x y z (3 times) / endloop /
 * endfacet" blocks, "endsolid"; keywords in any case; several solids may follow each other);
 * the rest is a binary file whose count disagrees with its size, or not STL. Stored facet
 * normals are ignored: TriMeshFinish takes them from the vertex order. Kept triangles keep the
 * file's order; zero-area ones (area <= 1e-12 longest edge^2) and exact duplicates (the same
 * three vertices in any order, found by sorting the sorted vertex triples: O(n log n)) are
 * dropped and counted. Errors name the file, the triangle (1-based, in file order) and, for
 * ASCII, the line. Binary coordinates are IEEE floats read byte by byte (little-endian on any
 * host).
 */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>
#include "sable.h" /* PETSC_SUCCESS on PETSc 3.18 */
#include "geom/trimesh.h"

#define STL_MSG 512

typedef struct {
  const char *path;
  char       *buf; /* the whole file, NUL-terminated */
  size_t      size;
  PetscInt    ntri, cap;
  double     *v;
  PetscInt    ndegen, nduplicate;
  int         code; /* PETSc error class of msg */
  char        msg[STL_MSG];
} StlRead;

static PetscErrorCode StlPush(StlRead *r, const double t[9])
{
  PetscFunctionBegin;
  if (r->ntri == r->cap) {
    double *w;

    r->cap = r->cap ? 2 * r->cap : 1024;
    PetscCall(PetscMalloc1(9 * (size_t)r->cap, &w));
    if (r->ntri) PetscCall(PetscArraycpy(w, r->v, 9 * (size_t)r->ntri));
    PetscCall(PetscFree(r->v));
    r->v = w;
  }
  PetscCall(PetscArraycpy(r->v + 9 * (size_t)r->ntri, t, 9));
  r->ntri++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static void StlFail(StlRead *r, int code, const char *fmt, ...)
{
  va_list ap;
  size_t  k;

  r->code = code;
  k       = (size_t)snprintf(r->msg, STL_MSG, "STL file %s: ", r->path);
  va_start(ap, fmt);
  if (k < STL_MSG) vsnprintf(r->msg + k, STL_MSG - k, fmt, ap);
  va_end(ap);
}

/* ---- binary ---- */

static uint32_t stl_u32(const unsigned char *b)
{
  return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
}

static double stl_f32(const unsigned char *b)
{
  uint32_t u = stl_u32(b);
  float    f;

  memcpy(&f, &u, sizeof f);
  return (double)f;
}

static PetscErrorCode StlParseBinary(StlRead *r, uint32_t n)
{
  const unsigned char *b = (const unsigned char *)r->buf + 84;
  double               t[9];

  PetscFunctionBegin;
  if ((uint64_t)n * 9 >= (uint64_t)PETSC_MAX_INT) {
    StlFail(r, PETSC_ERR_SUP, "%u triangles are more than this build's 32-bit PetscInt can index (at most %d): split the mesh or use a 64-bit-index PETSc", (unsigned)n, (int)(PETSC_MAX_INT / 9));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  for (uint32_t i = 0; i < n; i++, b += 50) {
    for (int k = 0; k < 9; k++) t[k] = stl_f32(b + 12 + 4 * k); /* bytes 0-11: the normal */
    for (int k = 0; k < 9; k++) {
      if (!isfinite(t[k])) {
        StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "triangle %u (binary) vertex %d has a non-finite coordinate (%g)", (unsigned)i + 1, k / 3 + 1, t[k]);
        PetscFunctionReturn(PETSC_SUCCESS);
      }
    }
    PetscCall(StlPush(r, t));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---- ASCII: a whitespace tokenizer that counts lines ---- */

typedef struct {
  char    *p;
  PetscInt line;    /* of the read position */
  PetscInt at;      /* the line of the current (last read) token */
  char     sep;     /* the separator consumed after it ('\n' ends its line) */
  char     tok[64]; /* the current token, truncated, for messages */
} StlLex;

/* The next token (NUL-terminated in place), or NULL at the end of the file. */
static char *stl_next(StlLex *x)
{
  char *s;

  while (*x->p && strchr(" \t\r\n\f\v", *x->p)) {
    if (*x->p == '\n') x->line++;
    x->p++;
  }
  if (!*x->p) return NULL;
  s     = x->p;
  x->at = x->line;
  while (*x->p && !strchr(" \t\r\n\f\v", *x->p)) x->p++;
  x->sep = *x->p;
  if (*x->p) { /* cut here; the separator is consumed, so count its newline */
    if (*x->p == '\n') x->line++;
    *x->p++ = 0;
  }
  snprintf(x->tok, sizeof x->tok, "%s", s);
  return s;
}

/* Skips the rest of the current token's line. */
static void stl_skip_line(StlLex *x)
{
  if (x->sep == '\n') return;
  while (*x->p && *x->p != '\n') x->p++;
}

/* Expects the keyword w inside facet tri; sets the error and returns 0 otherwise. */
static int stl_expect(StlRead *r, StlLex *x, const char *w, PetscInt tri)
{
  char *s = stl_next(x);

  if (!s) StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "truncated: end of file inside triangle %" PetscInt_FMT " (after line %" PetscInt_FMT ", expected '%s')", tri, x->at, w);
  else if (strcasecmp(s, w)) StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "triangle %" PetscInt_FMT " (line %" PetscInt_FMT "): expected '%s', found '%s'", tri, x->at, w, x->tok);
  return s && !strcasecmp(s, w);
}

/* Three numbers of triangle tri into c (finite when vertex; the normal is read and ignored). */
static int stl_numbers(StlRead *r, StlLex *x, PetscInt tri, int vertex, double c[3])
{
  for (int k = 0; k < 3; k++) {
    char *s = stl_next(x), *end;

    if (!s) {
      StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "truncated: end of file inside triangle %" PetscInt_FMT " (after line %" PetscInt_FMT ")", tri, x->at);
      return 0;
    }
    c[k] = strtod(s, &end);
    if (end == s || *end) {
      StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "triangle %" PetscInt_FMT " (line %" PetscInt_FMT "): '%s' is not a number", tri, x->at, x->tok);
      return 0;
    }
    if (vertex && !isfinite(c[k])) {
      StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "triangle %" PetscInt_FMT " (line %" PetscInt_FMT ") vertex %d has a non-finite coordinate (%s)", tri, x->at, vertex, x->tok);
      return 0;
    }
  }
  return 1;
}

/* One facet after its "facet" keyword: normal, loop of exactly 3 vertices, end. */
static PetscErrorCode StlParseFacet(StlRead *r, StlLex *x, PetscInt tri)
{
  double t[9], c[3];
  int    nv = 0;
  char  *s;

  PetscFunctionBegin;
  if (!stl_expect(r, x, "normal", tri) || !stl_numbers(r, x, tri, 0, c)) PetscFunctionReturn(PETSC_SUCCESS);
  if (!stl_expect(r, x, "outer", tri) || !stl_expect(r, x, "loop", tri)) PetscFunctionReturn(PETSC_SUCCESS);
  while ((s = stl_next(x)) && !strcasecmp(s, "vertex")) {
    if (!stl_numbers(r, x, tri, nv + 1, c)) PetscFunctionReturn(PETSC_SUCCESS);
    if (nv < 3) PetscCall(PetscArraycpy(t + 3 * nv, c, 3));
    nv++;
  }
  if (!s) {
    StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "truncated: end of file inside triangle %" PetscInt_FMT " (after line %" PetscInt_FMT ", %d vertices read)", tri, x->at, nv);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (strcasecmp(s, "endloop")) {
    StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "triangle %" PetscInt_FMT " (line %" PetscInt_FMT "): expected 'vertex' or 'endloop', found '%s'", tri, x->at, x->tok);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (nv != 3) {
    StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "triangle %" PetscInt_FMT " (its endloop on line %" PetscInt_FMT ") has %d vertices; an STL facet has 3", tri, x->at, nv);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (!stl_expect(r, x, "endfacet", tri)) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(StlPush(r, t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode StlParseAscii(StlRead *r)
{
  StlLex x = {r->buf, 1, 1, 0, ""};
  char  *s = stl_next(&x);

  PetscFunctionBegin;
  if (!s || strcasecmp(s, "solid")) {
    StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "not STL: text that does not begin with 'solid', and %zu bytes are not a binary STL (84 + 50 n)", r->size);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  stl_skip_line(&x); /* the solid's name */
  while (!r->msg[0]) {
    s = stl_next(&x);
    if (!s) StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "truncated: end of file after triangle %" PetscInt_FMT " (after line %" PetscInt_FMT ") without 'endsolid'", r->ntri, x.at);
    else if (!strcasecmp(s, "facet")) PetscCall(StlParseFacet(r, &x, r->ntri + 1));
    else if (!strcasecmp(s, "endsolid")) {
      stl_skip_line(&x);
      s = stl_next(&x);
      if (!s) break;
      if (strcasecmp(s, "solid")) StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "line %" PetscInt_FMT ", after triangle %" PetscInt_FMT ": expected 'solid' or the end of the file after 'endsolid', found '%s'", x.at, r->ntri, x.tok);
      else stl_skip_line(&x);
    } else StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "line %" PetscInt_FMT ", after triangle %" PetscInt_FMT ": expected 'facet' or 'endsolid', found '%s'", x.at, r->ntri, x.tok);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---- the file, its form, the skipped triangles ---- */

static PetscErrorCode StlLoad(StlRead *r)
{
  FILE *fp = fopen(r->path, "rb");
  long  len;

  PetscFunctionBegin;
  if (!fp) {
    StlFail(r, PETSC_ERR_FILE_OPEN, "cannot open (%s)", strerror(errno));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (fseek(fp, 0, SEEK_END) || (len = ftell(fp)) < 0 || fseek(fp, 0, SEEK_SET)) {
    StlFail(r, PETSC_ERR_FILE_READ, "cannot find its size (%s)", strerror(errno));
    fclose(fp);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  r->size = (size_t)len;
  PetscCall(PetscMalloc1(r->size + 1, &r->buf));
  if (fread(r->buf, 1, r->size, fp) != r->size) StlFail(r, PETSC_ERR_FILE_READ, "cannot read its %zu bytes (%s)", r->size, strerror(errno));
  r->buf[r->size] = 0;
  fclose(fp);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode StlParse(StlRead *r)
{
  uint32_t n    = r->size >= 84 ? stl_u32((const unsigned char *)r->buf + 80) : 0;
  uint64_t need = 84 + 50 * (uint64_t)n;

  PetscFunctionBegin;
  if (r->size == 0) StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "empty (0 bytes)");
  else if (r->size >= 84 && need == r->size) PetscCall(StlParseBinary(r, n));
  else if (!memchr(r->buf, 0, r->size)) PetscCall(StlParseAscii(r)); /* text */
  else if (r->size < 84) StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "not STL: %zu bytes with NUL bytes, shorter than the 84-byte binary header", r->size);
  else if (need > r->size) StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "truncated binary STL: the header counts %u triangles (%llu bytes), the file has %zu: triangle %llu is incomplete", (unsigned)n, (unsigned long long)need, r->size, (unsigned long long)(r->size - 84) / 50 + 1);
  else StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "binary STL: the header counts %u triangles (%llu bytes) but the file has %zu bytes, room for %zu: the count disagrees with the size after triangle %u", (unsigned)n, (unsigned long long)need, r->size, (r->size - 84) / 50, (unsigned)n);
  PetscFunctionReturn(PETSC_SUCCESS);
}

typedef struct {
  double   k[9]; /* the three vertices in lexicographic order */
  PetscInt i;
} StlKey;

static int stl_cmp3(const double *a, const double *b)
{
  for (int k = 0; k < 3; k++)
    if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
  return 0;
}

static int stl_cmp_key(const void *pa, const void *pb)
{
  const StlKey *a = pa, *b = pb;

  for (int k = 0; k < 9; k++)
    if (a->k[k] != b->k[k]) return a->k[k] < b->k[k] ? -1 : 1;
  return a->i < b->i ? -1 : a->i > b->i; /* the first in the file comes first and is kept */
}

/* 1 when triangle t has zero area: |(b - a) x (c - a)|/2 <= 1e-12 (longest edge)^2. */
static int stl_degenerate(const double *t)
{
  double e[3][3], x[3], l2 = 0;

  for (int j = 0; j < 3; j++) {
    for (int k = 0; k < 3; k++) e[j][k] = t[3 * ((j + 1) % 3) + k] - t[3 * j + k];
    l2 = PetscMax(l2, e[j][0] * e[j][0] + e[j][1] * e[j][1] + e[j][2] * e[j][2]);
  }
  x[0] = e[0][1] * e[2][2] - e[0][2] * e[2][1];
  x[1] = e[0][2] * e[2][0] - e[0][0] * e[2][2];
  x[2] = e[0][0] * e[2][1] - e[0][1] * e[2][0];
  return !(0.5 * sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) > 1e-12 * l2);
}

static int stl_same_key(const StlKey *a, const StlKey *b)
{
  for (int k = 0; k < 9; k++)
    if (a->k[k] != b->k[k]) return 0;
  return 1;
}

/* The key of triangle v: its vertices sorted lexicographically. */
static void stl_key(const double *v, PetscInt t, StlKey *key)
{
  int o[3] = {0, 1, 2};

  for (int a = 0; a < 2; a++)
    for (int b = 0; b < 2 - a; b++)
      if (stl_cmp3(v + 3 * o[b], v + 3 * o[b + 1]) > 0) {
        int w    = o[b];
        o[b]     = o[b + 1];
        o[b + 1] = w;
      }
  for (int j = 0; j < 3; j++)
    for (int k = 0; k < 3; k++) key->k[3 * j + k] = v[3 * o[j] + k];
  key->i = t;
}

/* Drops zero-area triangles, then duplicates (sorted keys), keeping the file order. */
static PetscErrorCode StlClean(StlRead *r)
{
  StlKey    *key;
  PetscBool *drop;
  PetscInt   nk = 0, kept = 0;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(r->ntri, &key));
  PetscCall(PetscCalloc1(r->ntri, &drop));
  for (PetscInt t = 0; t < r->ntri; t++) {
    if (stl_degenerate(r->v + 9 * (size_t)t)) {
      drop[t] = PETSC_TRUE;
      r->ndegen++;
    } else stl_key(r->v + 9 * (size_t)t, t, &key[nk++]);
  }
  qsort(key, (size_t)nk, sizeof *key, stl_cmp_key);
  for (PetscInt j = 1; j < nk; j++)
    if (stl_same_key(key + j, key + j - 1)) {
      drop[key[j].i] = PETSC_TRUE;
      r->nduplicate++;
    }
  for (PetscInt t = 0; t < r->ntri; t++)
    if (!drop[t]) {
      if (kept < t) PetscCall(PetscArraycpy(r->v + 9 * (size_t)kept, r->v + 9 * (size_t)t, 9));
      kept++;
    }
  if (r->ntri && !kept) StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "no triangles left: all %" PetscInt_FMT " are zero-area (%" PetscInt_FMT ") or duplicates (%" PetscInt_FMT ")", r->ntri, r->ndegen, r->nduplicate);
  else if (!r->ntri) StlFail(r, PETSC_ERR_FILE_UNEXPECTED, "no triangles");
  r->ntri = kept;
  PetscCall(PetscFree(key));
  PetscCall(PetscFree(drop));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Rank 0: the cleaned triangles of r->path, or r->msg. */
static PetscErrorCode StlReadLocal(StlRead *r)
{
  PetscFunctionBegin;
  PetscCall(StlLoad(r));
  if (!r->msg[0]) PetscCall(StlParse(r));
  if (!r->msg[0]) PetscCall(StlClean(r));
  PetscCall(PetscFree(r->buf));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TriMeshReadSTL(MPI_Comm comm, const char *path, TriMesh *m)
{
  StlRead     r;
  PetscMPIInt rank, count;
  PetscInt    head[4]; /* error class, triangles, zero-area, duplicates */

  PetscFunctionBegin;
  PetscCall(PetscMemzero(&r, sizeof r));
  PetscCall(PetscMemzero(m, sizeof *m));
  r.path = path;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) { /* any failure, an allocation's too, goes out through the broadcast: no rank waits for ever */
    PetscErrorCode ierr;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = StlReadLocal(&r);
    PetscCall(PetscPopErrorHandler());
    if (ierr && !r.msg[0]) StlFail(&r, (int)ierr, "could not be read (PETSc error %d: out of memory?)", (int)ierr);
    if (ierr) PetscCall(PetscFree(r.buf));
  }
  head[0] = r.msg[0] ? r.code : 0;
  head[1] = r.ntri;
  head[2] = r.ndegen;
  head[3] = r.nduplicate;
  PetscCallMPI(MPI_Bcast(head, 4, MPIU_INT, 0, comm));
  if (head[0]) { /* rank 0's words, on every rank */
    PetscCallMPI(MPI_Bcast(r.msg, STL_MSG, MPI_CHAR, 0, comm));
    PetscCall(PetscFree(r.v));
    SETERRQ(comm, (PetscErrorCode)head[0], "%s", r.msg);
  }
  PetscCall(PetscMPIIntCast(9 * head[1], &count));
  PetscCall(TriMeshCreate(head[1], m));
  if (rank == 0) PetscCall(PetscArraycpy(m->v, r.v, 9 * (size_t)head[1]));
  PetscCall(PetscFree(r.v));
  PetscCallMPI(MPI_Bcast(m->v, count, MPI_DOUBLE, 0, comm));
  m->ndegen     = head[2];
  m->nduplicate = head[3];
  PetscCall(TriMeshFinish(m));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---- life cycle and placement ---- */

PetscErrorCode TriMeshCreate(PetscInt ntri, TriMesh *m)
{
  PetscFunctionBegin;
  PetscCheck(ntri >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "TriMeshCreate: %" PetscInt_FMT " triangles must be >= 0", ntri);
  PetscCall(PetscMemzero(m, sizeof *m));
  m->ntri = ntri;
  PetscCall(PetscCalloc1(9 * (size_t)ntri, &m->v));
  PetscCall(PetscCalloc1(3 * (size_t)ntri, &m->n));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TriMeshFinish(TriMesh *m)
{
  PetscFunctionBegin;
  for (PetscInt t = 0; t < m->ntri; t++) {
    const double *a = m->v + 9 * (size_t)t, *b = a + 3, *c = a + 6;
    double        u[3], w[3], *n                           = m->n + 3 * (size_t)t, len;

    for (int k = 0; k < 3; k++) {
      u[k] = b[k] - a[k];
      w[k] = c[k] - a[k];
    }
    n[0] = u[1] * w[2] - u[2] * w[1];
    n[1] = u[2] * w[0] - u[0] * w[2];
    n[2] = u[0] * w[1] - u[1] * w[0];
    len  = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    PetscCheck(len > 0 && isfinite(len), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "triangle mesh: triangle %" PetscInt_FMT " (1-based) has no normal (zero area or non-finite vertices)", t + 1);
    for (int k = 0; k < 3; k++) n[k] /= len;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TriMeshDestroy(TriMesh *m)
{
  PetscFunctionBegin;
  if (!m) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscFree(m->v));
  PetscCall(PetscFree(m->n));
  PetscCall(PetscMemzero(m, sizeof *m));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* cos and sin of deg degrees, exact at multiples of 90 (so quarter turns move no vertex off). */
static void stl_cos_sin(double deg, double *c, double *s)
{
  double q = deg / 90;

  if (q == floor(q) && fabs(q) < 1e15) {
    const double cq[4] = {1, 0, -1, 0}, sq[4] = {0, 1, 0, -1};
    long         i = (long)fmod(q, 4.0);

    if (i < 0) i += 4;
    *c = cq[i];
    *s = sq[i];
  } else {
    *c = cos(deg * PETSC_PI / 180);
    *s = sin(deg * PETSC_PI / 180);
  }
}

PetscErrorCode TriMeshTransform(TriMesh *m, double scale, const double rot[3], const double shift[3])
{
  double R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

  PetscFunctionBegin;
  PetscCheck(scale > 0 && isfinite(scale), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "triangle mesh scale %g must be a finite number > 0", scale);
  for (int ax = 0; ax < 3; ax++) { /* R <- R_ax R: about x first, then y, then z (fixed axes) */
    double c, s, A[9] = {0}, T[9];
    int    i = (ax + 1) % 3, j = (ax + 2) % 3;

    PetscCheck(isfinite(rot[ax]), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "triangle mesh rotation about %c: %g degrees is not finite", 'x' + ax, rot[ax]);
    stl_cos_sin(rot[ax], &c, &s);
    A[4 * ax]    = 1;
    A[3 * i + i] = c, A[3 * i + j] = -s, A[3 * j + i] = s, A[3 * j + j] = c;
    for (int p = 0; p < 3; p++)
      for (int q = 0; q < 3; q++) T[3 * p + q] = A[3 * p] * R[q] + A[3 * p + 1] * R[3 + q] + A[3 * p + 2] * R[6 + q];
    PetscCall(PetscArraycpy(R, T, 9));
  }
  for (PetscInt t = 0; t < 3 * m->ntri; t++) {
    double *x = m->v + 3 * (size_t)t, y[3];

    for (int k = 0; k < 3; k++) y[k] = scale * (R[3 * k] * x[0] + R[3 * k + 1] * x[1] + R[3 * k + 2] * x[2]) + shift[k];
    for (int k = 0; k < 3; k++) x[k] = y[k];
  }
  PetscCall(TriMeshFinish(m));
  PetscFunctionReturn(PETSC_SUCCESS);
}
