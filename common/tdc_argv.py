"""tdc_argv - the command line of the Python tools (tdc_experiments.py,
tdc_sweep.py): `tool COMMAND [options] [positional...]`, as the C tools read
theirs (docs/tools.md).

    r = tdc_argv.command(argv, __doc__, "tdc-sweep", valued=("-j", "--sim"), flags=("--wait",))
    if isinstance(r, int):   # --help, no command, or a refused option: the exit code
        return r
    cmd, opts, pos = r

An option in `valued` takes the next argument as its value, one in `flags`
is True when given; anything else starting with "-" (but "-" alone, which is
positional) is refused with one line `tool: why` and EXIT.ARGS
(common/tdc_exit.h); no command prints the help and exits ARGS, --help
prints it and exits OK.  parse() alone raises UsageError."""
import sys

from tdc_exit import EXIT


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


def command(argv, doc, tool, valued=(), flags=()):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(doc)
        return EXIT.OK if len(argv) >= 2 else EXIT.ARGS
    try:
        opts, pos = parse(argv[2:], valued, flags)
    except UsageError as e:
        print("%s: %s" % (tool, e), file=sys.stderr)
        return EXIT.ARGS
    return argv[1], opts, pos
