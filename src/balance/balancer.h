/* The load balancer as an object: measures, decides when, computes cuts (balance.h) and moves
 * the DEM, and the fluid through the coupling, onto them. */
#pragma once
#include "coupling/coupling.h"
#include "balance/balance.h"

/* Load balancing (balancer.c; Golshan & Blais 2022): cell weights from the particle counts, new
 * per-axis cuts of the shared DMDA, fluid and particles moved onto them. cpl NULL: a dry run.
 * Life cycle: BalanceCreate -> BalanceSetFromOptions (-lb_scheme none|once|frequent|dynamic,
 * -lb_weight linear|quadratic|measured, -lb_alpha, -lb_beta, -lb_threshold, -lb_interval,
 * -lb_interval_time, -lb_step, -lb_time, -lb_max_sweeps, -lb_verbose) [-> BalanceCheckpointRead
 * on -restart] -> BalanceSetUp (after DemSetUp and CplSetUp) -> BalanceCheck after every step
 * -> BalanceView -> BalanceDestroy. All collective. */
typedef struct _p_Balance *Balance;
PetscErrorCode             BalanceCreate(Domain *dom, Dem dem, Cpl cpl, Balance *lb);
PetscErrorCode             BalanceSetFromOptions(Balance lb);
PetscErrorCode             BalanceSetUp(Balance lb);
/* Checks when the scheme says so (force: now, and rebalance whatever the threshold); moved
 * tells whether the cuts changed. Prints one line per check unless -lb_verbose 0. */
PetscErrorCode BalanceCheck(Balance lb, PetscBool force, PetscBool *moved);
/* The decomposition of the run's start, chosen from the particles (decompose.c): after DemSetUp
 * and before the fluid and the coupling are set up, on more than one rank, unless the user gave
 * any of -da_processors_x/y/z or the Domain holds a checkpoint's cuts, the process grid and cuts
 * with the smallest estimated largest rank load plus ghosts (balancer weights -lb_weight,
 * -lb_alpha, -lb_beta) replace PETSc's default when they lower that estimate by more than 5%,
 * and the DEM's particles move onto them. Prints one line: what was chosen and why. */
PetscErrorCode BalanceDecompose(Balance lb);
/* The current rank loads under the weight model: smallest, largest, mean. */
PetscErrorCode BalanceGetLoads(Balance lb, PetscReal *lmin, PetscReal *lmax, PetscReal *lavg);
/* The coupling whose fluid moves with the cuts (set before BalanceSetUp; NULL: a dry run). */
PetscErrorCode BalanceSetCoupling(Balance lb, Cpl cpl);
/* Whether -lb_scheme is other than none (known after BalanceSetFromOptions). */
PetscErrorCode BalanceIsActive(Balance lb, PetscBool *on);
PetscErrorCode BalanceView(Balance lb, PetscViewer viewer);
/* Checkpoints (datasets lb/...): the cuts of every axis with the grid and process grid they
 * belong to, the schedule (last check step, next check time, once done), the counters of
 * BalanceView and the measured weights. Write: collective, after BalanceSetUp (always, also with
 * -lb_scheme none: the cuts are the decomposition the DEM's per-rank state lives on). Read:
 * collective, on -restart right after the checkpoint is opened and BEFORE the DEM, the fluid and
 * the coupling are set up (it replaces the Domain's DMDA by one with the checkpoint's cuts; they
 * build their layouts from it), and before BalanceSetUp (which then keeps the schedule). On
 * another rank count, grid or process grid the checkpoint's cuts do not apply: the Domain keeps
 * the default cuts (the DEM redistributes its particles), the counters continue, the schedule
 * starts afresh (a check after the first step) and a log line says so. Errors name the file and
 * the dataset. */
PetscErrorCode BalanceCheckpointWrite(Balance lb, IoCkpt ck);
PetscErrorCode BalanceCheckpointRead(Balance lb, IoCkpt ck);
PetscErrorCode BalanceDestroy(Balance *lb);
