/* HDF5's single-writer/multiple-reader (SWMR) calls that its Fortran API (1.10) lacks, for
 * h5_swmr_m. In SWMR write mode HDF5 writes a flush's metadata children before their
 * parents, so that a writer killed at any moment leaves a file whose last flush is readable
 * (docs/output.md, "A killed run"). */
#include <hdf5.h>

/* Switch the open file (latest format, RDWR, only datasets open) to SWMR writing; 0 on
 * success, -1 on failure. */
int rc_h5_start_swmr_write(hid_t file_id)
{
    return H5Fstart_swmr_write(file_id) < 0 ? -1 : 0;
}

/* Open path for reading as a SWMR reader (a file whose SWMR writer was killed still carries
 * its 'open for writing' marks, which only a SWMR reader accepts; nothing is written to
 * the file); the file identifier, negative on failure. */
hid_t rc_h5_open_swmr_read(const char *path)
{
    return H5Fopen(path, H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT);
}
