/* peak_rss.c — run a command and write its peak resident memory, for bench/embree.py.
 *
 *   peak_rss OUT COMMAND [ARGS…]   runs COMMAND, writes its ru_maxrss in kB to the file OUT,
 *                                  and exits with COMMAND's exit code (127 if it did not start)
 *
 * Why a C program: a process forked from Python and then exec'd reports at least the Python
 * parent's own peak as its ru_maxrss (the kernel keeps the high-water mark of the memory the
 * process had before exec), so a 16 MB render measured that way read 42 MB. Forked from this
 * small process, COMMAND's ru_maxrss is its own.
 *
 * Build (embree.py does it, into /tmp): cc -O2 -o peak_rss peak_rss.c
 */
#include <stdio.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

int main(int argc, char **argv) {
    if (argc < 3) {
        fprintf(stderr, "usage: peak_rss OUT COMMAND [ARGS...]\n");
        return 2;
    }
    pid_t pid = fork();
    if (pid < 0) return 127;
    if (pid == 0) {
        execvp(argv[2], argv + 2);
        _exit(127);
    }
    int status;
    struct rusage usage;
    if (wait4(pid, &status, 0, &usage) != pid) return 127;
    FILE *out = fopen(argv[1], "w");
    if (!out) return 127;
    fprintf(out, "%ld\n", usage.ru_maxrss);
    fclose(out);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}
