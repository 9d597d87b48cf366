/* File identity for fsys_m: whether two paths name the same file (through any mix of
 * relative paths, symbolic and hard links). Kept in C because struct stat's layout is
 * platform-specific. */
#include <sys/stat.h>

/* 1 when both paths exist and are the same file (same device and inode), else 0. */
int rc_same_file(const char *a, const char *b)
{
    struct stat sa, sb;

    if (stat(a, &sa) != 0 || stat(b, &sb) != 0)
        return 0;
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}
