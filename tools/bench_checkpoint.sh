#!/bin/sh
# Checkpoint benchmark: the cost of an exact checkpoint of a settled bed of 10^5 and 10^6 glass
# spheres (the settle scene of cases/settle, linear law with tangential history), against the
# cost of its steps. The bed: the 10,000-sphere settle box run to 0.8 s (tools/bench.sh's, reused
# when the current binary made it) tiled 10 times (5 x 2) or 100 times (10 x 10) side by side in
# a wider box of the same height without the inner walls (ids renumbered), then 200 steps so that
# the contacts across the seams and their springs exist; that run's final checkpoint is the
# restart point. From it, 3 runs each: -restart, 120 steps, a checkpoint at the end. Quoted
# (medians of the 3): the write time and file size ("checkpoint: PATH", then "written in X s, Y
# MB"), the time from opening the checkpoint to the end of the set-up ("restart: PATH", then
# "read and set up in X s"), the mean step ((loop time - write time) / 120), per particle, and
# the ratio write / (100 steps), which must stay below 1. Files go to the page cache (neither the
# write nor the read waits for the disk). 10^5 on 1 and 2 ranks, 10^6 on 1 rank.
#   tools/bench_checkpoint.sh            both sizes
#   SIZES=100k RANKS_100K=1 tools/bench_checkpoint.sh
# Output in bench-out/ckpt/; the table on stdout.
set -eu
cd "$(dirname "$0")/.."
[ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
SIZES=${SIZES:-100k 1m}
RANKS_100K=${RANKS_100K:-1 2}
RANKS_1M=${RANKS_1M:-1}
STEPS=120
O=bench-out/ckpt
mkdir -p $O
A=0.2898 H=0.4347 # the settle box of cases/settle/settle.opts
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
# the tile: tools/bench.sh's settled 10k bed (the same run) when this binary made it
tile=bench-out/settle_10k/sable_000001.h5
if [ ! -f $tile ] || [ bin/sable -nt $tile ]; then
  rm -rf bench-out/settle_10k
  bin/sable -options_file cases/settle/settle.opts -dem_t_end 0.8 -io_interval 0.8 -dem_progress_interval 0 -io_dir bench-out/settle_10k > bench-out/settle_10k.log
fi
cat > $O/tile.py <<'PY'
#!/usr/bin/python3
# tile.py IN OUT TX TY LX LY: the particles of frame IN repeated TX x TY times along x and y,
# every other tile mirrored
import sys, h5py, numpy as np
src, dst, tx, ty, lx, ly = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), float(sys.argv[5]), float(sys.argv[6])
with h5py.File(src, "r") as f, h5py.File(dst, "w") as g:
    p = f["particles"]
    n, idmax = p["position"].shape[0], int(p["id"][()].max()) + 1
    for name in ("position", "velocity", "angular_velocity", "quaternion", "radius", "id", "shape"):
        a = p[name][()]
        out = []
        for j in range(ty):
            for i in range(tx):
                b = a.copy()
                if name == "position":  # odd tiles mirrored: each seam is a plane of symmetry
                    b[:, 0] = i * lx + (lx - b[:, 0] if i % 2 else b[:, 0])
                    b[:, 1] = j * ly + (ly - b[:, 1] if j % 2 else b[:, 1])
                if name == "velocity":
                    b[:, 0] *= -1 if i % 2 else 1
                    b[:, 1] *= -1 if j % 2 else 1
                if name == "angular_velocity":  # a pseudo-vector: the mirrored axis keeps its sign
                    b[:, 1] *= -1 if i % 2 else 1
                    b[:, 2] *= -1 if i % 2 else 1
                    b[:, 0] *= -1 if j % 2 else 1
                    b[:, 2] *= -1 if j % 2 else 1
                if name == "id":
                    b = b + (j * tx + i) * idmax
                out.append(b)
        g.create_dataset("particles/" + name, data=np.concatenate(out))
    g.attrs["time"] = 0.0
PY
chmod +x $O/tile.py
echo "checkpoint bench, $(date -u '+%Y-%m-%d %H:%M UTC'), load average $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
echo "| N | ranks | write (s) | write (us / particle) | read + set-up (s) | read + set-up (us / particle) | size (MB) | bytes / particle | step (s) | write / 100 steps |"
echo "|---|---|---|---|---|---|---|---|---|---|"
: > $O/table.md
for s in $SIZES; do
  case $s in
    100k) TX=5 TY=2 RANKS=$RANKS_100K ;;
    1m) TX=10 TY=10 RANKS=$RANKS_1M ;;
    *) echo "unknown size $s (100k or 1m)"; exit 1 ;;
  esac
  N=$((TX * TY * 10000))
  LX=$(echo "$TX * $A" | bc -l) LY=$(echo "$TY * $A" | bc -l)
  $O/tile.py $tile $O/bed_$s.h5 $TX $TY $A $A
  GEO="-options_file cases/settle/settle.opts -domain_lo 0,0,0 -domain_hi $LX,$LY,$H -dem_box 0,0,0,$LX,$LY,$H -dem_lattice 0,0,0 -dem_progress_interval 0 -io_interval 0"
  for r in $RANKS; do
    d=$O/$s.np$r
    rm -rf $d; mkdir -p $d
    mpiexec -n $r bin/sable $GEO -dem_init_file $O/bed_$s.h5 -dem_t_end 0.002 -io_checkpoint_interval 1 -io_checkpoint_keep 1 -io_dir $d/prep > $d.prep.log
    ck=$(sed -n 's/^checkpoint: //p' $d.prep.log | tail -n 1)
    for k in 1 2 3; do
      mpiexec -n $r bin/sable $GEO -restart $ck -dem_t_end 0.0032 -io_checkpoint_interval 1 -io_checkpoint_keep 1 -io_dir $d/run$k > $d.$k.log
      rm -rf $d/run$k
    done
    rm -rf $d/prep
    w=$(cat $d.[123].log | sed -n 's/^  written in \([0-9.]*\) s.*/\1/p' | median)
    mb=$(cat $d.[123].log | sed -n 's/^  written in .* s, \([0-9.]*\) MB.*/\1/p' | median)
    rd=$(cat $d.[123].log | sed -n 's/^  read and set up in \([0-9.]*\) s.*/\1/p' | median)
    st=$(for k in 1 2 3; do
      lp=$(sed -n 's/^done: .* steps in \([0-9.]*\) s.*/\1/p' $d.$k.log)
      wk=$(sed -n 's/^  written in \([0-9.]*\) s.*/\1/p' $d.$k.log)
      echo "($lp - $wk) / $STEPS" | bc -l
    done | median)
    awk -v n=$N -v r=$r -v w=$w -v rd=$rd -v mb=$mb -v st=$st 'BEGIN {
      printf "| %d | %d | %.3f | %.2f | %.3f | %.2f | %.1f | %.0f | %.4f | %.3f |\n", n, r, w, 1e6 * w / n, rd, 1e6 * rd / n, mb, mb * 1048576 / n, st, w / (100 * st) }' | tee -a $O/table.md
  done
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
awk -F'|' '$2 + 0 == 1000000 && $3 + 0 == 1 {r = $11 + 0; printf "at 10^6 spheres a checkpoint costs %.3f x 100 steps (target < 1: %s)\n", r, r < 1 ? "met" : "NOT met"}' $O/table.md
