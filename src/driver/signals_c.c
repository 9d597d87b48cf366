/* Clean stop on a scheduler's signal (SIGTERM, SIGINT, SIGUSR1: what Slurm's --signal and
 * scancel send, and Ctrl-C): the handler only records the signal in a volatile
 * sig_atomic_t; run_m polls it once per time step through stop_signal_m and stops after
 * the step. SA_RESETHAND restores the default action, so a second signal of the same kind
 * ends the program at once (a second Ctrl-C when the clean stop takes too long). */
#include <signal.h>
#include <string.h>

/* in the order of stop_signal_m's names */
static const int signals[] = {SIGTERM, SIGINT, SIGUSR1};
static volatile sig_atomic_t received = 0;

static void record_signal(int sig)
{
    received = sig;
}

/* Install the handler for SIGTERM, SIGINT and SIGUSR1 and unblock them, and ignore SIGXFSZ;
 * 0 on success, -1 on failure. A process may inherit them blocked (the signal mask survives
 * exec): then a scheduler's signal would stay pending and the run never stop; one that is
 * already pending is delivered here, once the handler records it. SIGXFSZ's default action
 * kills a process that writes past its file size limit (ulimit -f): ignored, the write fails
 * with EFBIG, and the output writer stops with a message and exit status 4 as on a full disk. */
int rc_install_stop_handlers(void)
{
    struct sigaction action;
    sigset_t stop_set;
    size_t k;

    memset(&action, 0, sizeof action);
    action.sa_handler = record_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART | SA_RESETHAND;
    sigemptyset(&stop_set);
    for (k = 0; k < sizeof signals / sizeof signals[0]; k++)
        if (sigaction(signals[k], &action, NULL) != 0 || sigaddset(&stop_set, signals[k]) != 0)
            return -1;
    action.sa_handler = SIG_IGN;
    action.sa_flags = 0;
    if (sigaction(SIGXFSZ, &action, NULL) != 0)
        return -1;
    return sigprocmask(SIG_UNBLOCK, &stop_set, NULL) == 0 ? 0 : -1;
}

/* Which stop signal was received since the handlers were installed: 1 SIGTERM, 2 SIGINT,
 * 3 SIGUSR1, 0 none. */
int rc_stop_signal(void)
{
    size_t k;

    for (k = 0; k < sizeof signals / sizeof signals[0]; k++)
        if (received == signals[k])
            return (int)k + 1;
    return 0;
}
