"""One exit-code convention for every ``gearloss`` command (printed by ``gearloss --help``, docs/reference/cli.md).

=====  ===============================================================================================
code   meaning
=====  ===============================================================================================
0      ok: the result is computed, converged and inside the model's validity
1      a result is computed but did not converge, or lies outside the model's validity (it is printed,
       flagged ``"valid": false`` with the reasons, or ``"converged": false``)
2      bad input: an option outside its accepted range, an unknown name, a file that cannot be read (nothing
       is computed), or with ``--strict`` a result outside the model's validity (refused, not printed)
3      a stage cannot produce its result (e.g. the fit when the data cannot determine the regression)
130    interrupted by SIGINT (Ctrl-C); what is finished is kept and the command that resumes is printed
143    terminated by SIGTERM; as 130
=====  ===============================================================================================

With ``--json`` every error is also one JSON object on stdout (``{"error": {...}}``, :func:`error_payload`).
"""

from __future__ import annotations

OK = 0
NOT_VALID = 1
BAD_INPUT = 2
STAGE_FAILED = 3
SIGINT = 130
SIGTERM = 143

SIGNAL_EXIT = {"SIGINT": SIGINT, "SIGTERM": SIGTERM}
"""Exit code of an interrupted command by the name of the signal that stopped it."""

TABLE: tuple[tuple[int, str, str], ...] = (
    (OK, "ok", "result computed, converged and inside the model's validity"),
    (NOT_VALID, "not_valid", "result computed but not converged or outside the model's validity (flagged in the "
                             "output: \"converged\": false or \"valid\": false with the reasons)"),
    (BAD_INPUT, "bad_input", "bad input (an option outside its range, an unknown name, an unreadable file; nothing "
                             "is computed) or, with --strict, a result outside the model's validity (not printed)"),
    (STAGE_FAILED, "stage_failed", "a stage cannot produce its result (e.g. the fit when the data cannot "
                                   "determine the regression)"),
    (SIGINT, "interrupted", "interrupted by SIGINT (Ctrl-C): finished work is kept, the resume command is printed"),
    (SIGTERM, "terminated", "terminated by SIGTERM: as 130"),
)
"""(code, kind, meaning) of every exit code."""

KIND = {code: kind for code, kind, _ in TABLE}


def table_text(indent: str = "  ") -> str:
    """The exit-code table as plain text (the epilog of ``gearloss --help``)."""
    return "\n".join(f"{indent}{code:>3}  {meaning}" for code, _, meaning in TABLE)


def table_markdown() -> str:
    """The exit-code table as a Markdown table (docs/reference/cli.md holds a copy; a test compares them)."""
    rows = ["| exit code | meaning |", "|---|---|"]
    rows += [f"| {code} | {meaning} |" for code, _, meaning in TABLE]
    return "\n".join(rows)


class Interrupted(Exception):
    """A command stopped by SIGINT or SIGTERM after keeping what it finished; ``exit_code`` 130 or 143.

    Parameters
    ----------
    signal_name : str
        ``SIGINT`` or ``SIGTERM`` [-].
    what : str
        What was interrupted, for the message [-].
    resume_command : str, optional
        The command that continues it, printed with the error [-].
    """

    def __init__(self, signal_name: str, what: str, resume_command: str | None = None):
        self.signal_name = signal_name
        self.resume_command = resume_command
        message = f"{what} interrupted by {signal_name}"
        if resume_command:
            message += f"; finished work is kept, resume with: {resume_command}"
        super().__init__(message)

    @property
    def exit_code(self) -> int:
        return SIGNAL_EXIT.get(self.signal_name, SIGINT)


def error_payload(code: int, message: str, **fields) -> dict:
    """The JSON object of an error (``--json``): ``{"error": {"exit_code", "kind", "message", ...}}``."""
    return {"error": {"exit_code": code, "kind": KIND.get(code, "error"), "message": message,
                      **{k: v for k, v in fields.items() if v is not None}}}
