"""The gearloss command line: one console script with sub-command groups.

Each group lives in its own module (``cli_contact``, ``cli_dataset``, ``cli_surrogate``, ``cli_gear``, ...) that
exposes ``register(subparsers)``; heavy imports happen inside the handlers so ``gearloss --help`` stays fast, and a
command registers only its own group (``gearloss contact solve`` does not build the gear options).
Output goes through :func:`workflows.cli_output.emit`; every error goes through :func:`workflows.cli_output.fail`
(one line on stderr naming the option as typed, and with ``--json`` a JSON object on stdout), with the exit codes
of :mod:`workflows.exit_codes`.
"""

from __future__ import annotations

import argparse
import importlib
import os
import shlex
import signal
import sys
from contextlib import contextmanager

from ehl_dataset.validation import InputError, SolverError

from . import exit_codes
from .cli_help import GearlossParser, UsageError

GROUPS = {"lubricant": "workflows.cli_lubricant", "contact": "workflows.cli_contact",
          "dataset": "workflows.cli_dataset", "surrogate": "workflows.cli_surrogate", "gear": "workflows.cli_gear",
          "pipeline": "workflows.cli_pipeline", "report": "workflows.cli_report",
          "accuracy": "workflows.cli_accuracy", "roughness": "workflows.cli_roughness"}
"""The command groups, in the order of ``gearloss --help``, and the module that adds each group's sub-commands
(``register(subparsers)``), imported when the group is registered."""

DESCRIPTION = """\
gearloss: mixed-EHL line contacts -> a fitted friction surrogate -> helical gear power loss and efficiency
(after Li & Kahraman 2009). Every command accepts --json (one JSON object, SI units); '<command> --help' lists
its options with their defaults."""


def version_text() -> str:
    """``gearloss --version``: the package version and the EHL solver version (the one datasets record), read
    without importing the solver (:mod:`workflows.cli_version`)."""
    from .cli_version import version_text as text

    return text()


class _VersionAction(argparse.Action):
    def __init__(self, option_strings, dest=argparse.SUPPRESS, default=argparse.SUPPRESS, help=None):
        super().__init__(option_strings=option_strings, dest=dest, default=default, nargs=0, help=help)

    def __call__(self, parser, namespace, values, option_string=None):
        print(version_text())
        parser.exit(0)


def build_parser(groups=None) -> argparse.ArgumentParser:
    """The ``gearloss`` argument parser.

    Parameters
    ----------
    groups : iterable of str or None
        Names of the command groups to register (keys of :data:`GROUPS`); None: all of them [-].

    Returns
    -------
    argparse.ArgumentParser
        The parser; a command's handler is ``args.handler``.
    """
    parser = GearlossParser(prog="gearloss", description=DESCRIPTION,
                            epilog="exit codes (every command):\n" + exit_codes.table_text())
    parser.add_argument("--version", action=_VersionAction,
                        help="print the package and EHL solver versions and exit")
    subparsers = parser.add_subparsers(dest="group", metavar="GROUP")
    for name in GROUPS if groups is None else groups:
        importlib.import_module(GROUPS[name]).register(subparsers)
    return parser


class _Terminated(BaseException):
    """SIGTERM outside a runner (which handles it itself and stops cleanly)."""


class _CtrlC(KeyboardInterrupt):
    """SIGINT as raised by gearloss's own handler. A subclass on purpose: CPython kills a process with SIGINT at exit
    when an exception of exactly type KeyboardInterrupt left code run through its C-level ``PyRun_*`` calls (as
    happens when Ctrl-C arrives during some imports), even after ``main`` caught it and returned 130."""


class _Redelivery:
    """Sends a caught signal to this process again every ``interval_s`` until :meth:`stop`.

    A signal handler's exception is lost when it lands where Python cannot propagate it: a ctypes callback (numba's
    object-cache hook), a ``__del__`` or a weakref callback print it as "Exception ignored" and run
    on. Sending the signal again raises it anew, at a later bytecode of the main thread, until it gets through."""

    def __init__(self, signum: int, interval_s: float):
        import threading

        self._signum = signum
        self._interval_s = interval_s
        self._lock = threading.Lock()
        self._stopped = threading.Event()
        self._thread = threading.Thread(target=self._run, name=f"gearloss-resend-{signum}", daemon=True)
        self._thread.start()

    def _run(self) -> None:
        import os

        while not self._stopped.wait(self._interval_s):
            with self._lock:
                if self._stopped.is_set():
                    return
                os.kill(os.getpid(), self._signum)

    def stop(self) -> None:
        with self._lock:
            self._stopped.set()
        self._thread.join(timeout=1.0)


RESEND_INTERVAL_S = 2.0
"""Seconds between re-sends of a signal whose exception has not yet stopped the command (see :class:`_Redelivery`)."""


@contextmanager
def _signals_raise():
    """SIGTERM raises :class:`_Terminated` in the main thread (exit 143 with a message, not a silent death); SIGINT,
    unless ignored, raises :class:`_CtrlC` (exit 130). A caught signal is sent again every
    :data:`RESEND_INTERVAL_S` until the command has stopped (:class:`_Redelivery`), and the "Exception ignored"
    report of one that was lost is silenced: the re-send stands in for it."""
    resends: dict[int, _Redelivery] = {}

    def raise_and_resend(signum: int, exception: type[BaseException]):
        if signum not in resends:
            resends[signum] = _Redelivery(signum, RESEND_INTERVAL_S)
        raise exception()

    def on_sigterm(signum, frame):
        raise_and_resend(signum, _Terminated)

    def on_sigint(signum, frame):
        raise_and_resend(signum, _CtrlC)

    def quiet_lost_signal(unraisable):
        if not isinstance(unraisable.exc_value, (_Terminated, _CtrlC)):
            previous_hook(unraisable)

    try:
        previous_term = signal.signal(signal.SIGTERM, on_sigterm)
    except ValueError:  # not the main thread (e.g. a test runner's worker thread)
        yield
        return
    previous_int = signal.getsignal(signal.SIGINT)
    if previous_int is signal.default_int_handler:
        signal.signal(signal.SIGINT, on_sigint)
    previous_hook = sys.unraisablehook
    sys.unraisablehook = quiet_lost_signal
    try:
        yield
    finally:
        for resend in resends.values():
            resend.stop()
        sys.unraisablehook = previous_hook
        signal.signal(signal.SIGTERM, previous_term)
        if previous_int is signal.default_int_handler:
            signal.signal(signal.SIGINT, previous_int)


def _signal_behind(err: BaseException) -> BaseException | None:
    """The interrupt (:class:`KeyboardInterrupt` or :class:`_Terminated`) in the cause/context chain of ``err``."""
    seen = set()
    while err is not None and id(err) not in seen:
        seen.add(id(err))
        if isinstance(err, (KeyboardInterrupt, _Terminated)):
            return err
        err = err.__cause__ or err.__context__
    return None


def _leave_objects_to_the_os() -> None:
    """Exclude every object alive now from garbage collection (:func:`gc.freeze`), so that the interpreter's
    finalisation does not take numba's compiler state apart object by object: 0.2-0.3 s of CPU after a contact
    solve, as much as the solve. atexit handlers and the flush of stdout and stderr still run; finalisers of objects
    in reference cycles do not, so a command opts in (``set_defaults(leave_objects_at_exit=True)``) only when it
    writes nothing but its output."""
    import gc

    gc.freeze()


def main(argv: list[str] | None = None) -> int:
    """Run ``gearloss`` with the arguments ``argv``.

    Parameters
    ----------
    argv : list of str or None
        The arguments after the program name; None: those of the process (``sys.argv``), i.e. run as the program,
        which may end without the interpreter's object teardown (:func:`_leave_objects_to_the_os`) [-].

    Returns
    -------
    int
        The exit code (:mod:`workflows.exit_codes`).
    """
    from .cli_output import fail

    as_program = argv is None
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv == ["--version"]:  # before the parser: building it imports every command group's options
        print(version_text())
        return 0
    as_json = "--json" in argv
    # a command registers only its group; anything else (no group, --help, a mistyped group) gets every group
    parser = build_parser([argv[0]] if argv and argv[0] in GROUPS else None)
    try:
        args = parser.parse_args(argv)
    except UsageError as err:
        return fail(exit_codes.BAD_INPUT, str(err), as_json, prog=err.prog, option=err.option, value=err.value,
                    accepted=err.accepted)
    except SystemExit as err:  # --help, --version
        return int(err.code or 0)
    handler = getattr(args, "handler", None)
    if handler is None:
        parser.print_help()
        return exit_codes.BAD_INPUT
    args.argv = argv
    args.command_line = "gearloss " + shlex.join(argv)
    try:
        with _signals_raise():
            code = int(handler(args) or 0)
        if as_program and getattr(args, "leave_objects_at_exit", False):
            _leave_objects_to_the_os()
        return code
    except InputError as err:
        from .cli_errors import translate

        err = translate(err, args)
        return fail(exit_codes.BAD_INPUT, str(err), as_json, parameter=err.parameter, value=err.value,
                    accepted=err.accepted)
    except SolverError as err:
        return fail(exit_codes.STAGE_FAILED, f"solver error: {err}", as_json)
    except exit_codes.Interrupted as err:
        return fail(err.exit_code, str(err), as_json, resume_command=err.resume_command)
    except (KeyboardInterrupt, _Terminated, SystemError, ImportError) as err:
        # a signal handler's exception raised while compiled code ran comes back as the cause of another error:
        # numba's SystemError ("returned a result with an exception set"), or the ImportError ("initialization
        # failed") of an extension module whose initialisation it interrupted (scipy's HiGHS wrapper, for one)
        interrupt = _signal_behind(err)
        if interrupt is None:
            raise
        if isinstance(interrupt, KeyboardInterrupt):
            return fail(exit_codes.SIGINT, f"interrupted by SIGINT: {args.command_line} stopped", as_json)
        return fail(exit_codes.SIGTERM, f"terminated by SIGTERM: {args.command_line} stopped", as_json)
    except BrokenPipeError:  # the reader of the output closed it (`gearloss ... | head -1`): nothing left to say
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())  # so that the interpreter's final flush does not fail again
        return 0
    except FileNotFoundError as err:
        return fail(exit_codes.BAD_INPUT, f"file not found: {err.filename or err}", as_json, value=err.filename)
    except (IsADirectoryError, NotADirectoryError, PermissionError) as err:
        return fail(exit_codes.BAD_INPUT, f"cannot use {err.filename or err}: {err.strerror or err}", as_json,
                    value=err.filename)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
