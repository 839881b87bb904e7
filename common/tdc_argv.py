"""tdc_argv - the command line of the Python tools (tdc_experiments.py,
tdc_sweep.py): `tool COMMAND [options] [positional...]`, as the C tools read
theirs (docs/tools.md).

    opts, pos = tdc_argv.parse(rest, valued=("-j", "--sim"), flags=("--wait",))

An option in `valued` takes the next argument as its value, one in `flags`
is True when given; anything else starting with "-" (but "-" alone, which is
positional) is refused.  A refusal raises UsageError with the one-line why;
the tool prints it and exits with EXIT.ARGS (common/tdc_exit.h)."""


class UsageError(Exception):
    pass


def parse(rest, valued=(), flags=()):
    opts, pos = {}, []
    it = iter(rest)
    for a in it:
        if a in valued:
            v = next(it, None)
            if v is None:
                raise UsageError("%s needs a value" % a)
            opts[a] = v
        elif a in flags:
            opts[a] = True
        elif a.startswith("-") and a != "-":
            raise UsageError("unknown option '%s' (see --help)" % a)
        else:
            pos.append(a)
    return opts, pos
