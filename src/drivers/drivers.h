/* The run drivers: the dry and the coupled loops, their progress lines and summaries. main picks
 * one; each builds the objects its run needs beside the given Domain, Dem and Io. */
#pragma once
#include "balance/balancer.h"

/* The coupled driver (coupled.c): builds Fluid and Cpl beside the given Dem (options read, not set
 * up), runs to -cpl_t_end with progress lines and output through io. With help set it only reads
 * the options (so -help lists them). Collective. */
PetscErrorCode CplRunCase(Domain *dom, Dem dem, Io io, PetscBool help);
/* Whether the options ask for a coupled run (any -cpl_ or -fluid_ option given). */
PetscErrorCode CplRequested(PetscBool *on);
