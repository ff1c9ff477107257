/* Private to src/io: what the writer (io.c) and the reader (read.c) share. HDF5's own error stack
 * is silenced (a dozen lines per failure); each failure becomes one message of ours naming the
 * file, the dataset and, from the innermost entry of the stack, what HDF5 says went wrong. */
#pragma once
#include "io/io.h"
#include <hdf5.h>

/* Silences HDF5's printing of its error stack. Called before every HDF5 use of src/io. */
static inline void io_quiet(void)
{
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
}

/* The innermost entry of HDF5's error stack, "function: description", in buf ("" when the stack
 * is empty). Call right after the failed call: any later HDF5 call clears the stack. */
void io_h5_last_error(char *buf, size_t len);
