#!/usr/bin/python3
"""frames_equal.py A B: compares two Sable HDF5 files (frames or checkpoints) dataset by dataset,
bytes, shape and type: every dataset of A must be in B with the same bytes. Prints
"<datasets of A> <differing> <names of the differing ones>". Used by the checkpoint tests,
whose reference is the uninterrupted run's frame."""
import sys

import h5py

a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
names = []
a.visit(lambda n: names.append(n) if isinstance(a[n], h5py.Dataset) else None)
diff = [n for n in names if n not in b or a[n].shape != b[n].shape or a[n].dtype != b[n].dtype or a[n][()].tobytes() != b[n][()].tobytes()]
print(len(names), len(diff), " ".join(diff))
