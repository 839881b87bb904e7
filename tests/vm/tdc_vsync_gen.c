/*
 * tdc_vsync_gen.c - a vsync source for `make test-vm`: drives a gpio-sim
 * line through its sysfs "pull" attribute at a fixed rate (absolute
 * CLOCK_MONOTONIC deadlines, so the rate does not drift), leaving out one
 * pulse in every `skip_every` to emulate missed frames.
 * Usage: tdc_vsync_gen <.../sim_gpioN/pull> <hz> <pulses> <skip_every|0>
 */
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static void set_pull(const char *path, const char *v)
{
    int fd = open(path, O_WRONLY);
    if (fd < 0 || write(fd, v, strlen(v)) < 0) {
        perror(path);
        exit(1);
    }
    close(fd);
}

static void add_ns(struct timespec *t, long ns)
{
    t->tv_nsec += ns;
    while (t->tv_nsec >= 1000000000L) {
        t->tv_nsec -= 1000000000L;
        t->tv_sec++;
    }
}

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: tdc_vsync_gen <pull attribute> <hz> <pulses> <skip_every>\n");
        return 1;
    }
    double hz = atof(argv[2]);
    long pulses = atol(argv[3]), skip = atol(argv[4]);
    if (!(hz > 0 && hz < 10000) || pulses < 1) {
        fprintf(stderr, "tdc_vsync_gen: bad rate or count\n");
        return 1;
    }
    long half = (long)(0.5e9 / hz);
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    set_pull(argv[1], "pull-down");
    for (long i = 0; i < pulses; i++) {
        add_ns(&t, half);
        clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, NULL);
        if (!(skip > 0 && i % skip == skip - 1)) set_pull(argv[1], "pull-up");
        add_ns(&t, half);
        clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, NULL);
        set_pull(argv[1], "pull-down");
    }
    return 0;
}
