/* Provenance for run_attributes_m: the current time in UTC as ISO 8601 and the host name.
 * In C because Fortran has neither gmtime nor gethostname. */
#include <string.h>
#include <time.h>
#include <unistd.h>

/* Write 'YYYY-MM-DDThh:mm:ssZ' (20 characters and a NUL) into buf of size n; 0 on success. */
int rc_utc_now(char *buf, int n)
{
    time_t now = time(NULL);
    struct tm utc;

    if (now == (time_t)-1 || gmtime_r(&now, &utc) == NULL)
        return -1;
    return strftime(buf, (size_t)n, "%Y-%m-%dT%H:%M:%SZ", &utc) > 0 ? 0 : -1;
}

/* The host name, NUL-terminated, into buf of size n; 0 on success. */
int rc_hostname(char *buf, int n)
{
    if (gethostname(buf, (size_t)n) != 0)
        return -1;
    buf[n - 1] = '\0';
    return 0;
}
