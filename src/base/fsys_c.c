/* What fsys_m needs of POSIX in C: the errno of each failure as a return value, and file
 * identity (struct stat's layout is platform-specific). */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

/* 1 when both paths exist and are the same file (same device and inode), else 0. */
int rc_same_file(const char *a, const char *b)
{
    struct stat sa, sb;

    if (stat(a, &sa) != 0 || stat(b, &sb) != 0)
        return 0;
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

/* errno when it says that a write failed for want of space or by a device fault, else 0. */
int rc_write_errno(void)
{
    int e = errno;

    return (e == ENOSPC || e == EFBIG || e == EDQUOT || e == EIO || e == EROFS) ? e : 0;
}

/* posix_fallocate of the first `bytes` bytes of `path` (fsys_m's reserve_file_size): 0 also
 * when the file system cannot reserve space at all, else the errno. */
int rc_reserve_file_size(const char *path, long long bytes)
{
    int fd, rc;

    fd = open(path, O_WRONLY);
    if (fd < 0)
        return errno;
    rc = posix_fallocate(fd, 0, (off_t)bytes);
    close(fd);
    if (rc == EOPNOTSUPP || rc == EINVAL)
        return 0;
    return rc;
}

/* fsys_m's operation op (its OP_*) on path a: 1 mkdir(a, 0755), 2 rename(a, b), 3 create (or
 * truncate) a as an empty file (fopen, not open(2), whose variadic prototype bind(C) cannot
 * describe). 0, or the errno of the failure. */
int rc_path_op(int op, const char *a, const char *b)
{
    FILE *stream;

    if (op == 1)
        return mkdir(a, 0755) == 0 ? 0 : errno;
    if (op == 2)
        return rename(a, b) == 0 ? 0 : errno;
    stream = fopen(a, "w");
    if (stream == NULL)
        return errno;
    return fclose(stream) == 0 ? 0 : errno;
}
