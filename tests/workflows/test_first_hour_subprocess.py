"""The first hour of a new user with real processes: the README's main job, the smoke pipeline and the main job again, in any
order, without collisions; Ctrl-C gives exit 130 and the command that resumes; SIGTERM 143.

The main job (`gearloss pipeline quick`) takes about two CPU-minutes (79 s with 2 workers), so here it runs with a
tiny wall-time budget per point
(`--time-limit-s 0.5`) and is interrupted with SIGINT a few seconds after it has started computing; the smoke
pipeline runs to its end (about 10 s).
"""

import os
import select
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from ehl_dataset.dataset.store import read_metadata

REPO = Path(__file__).resolve().parents[2]
# the main job with every effect forced: the deterministic solver on the 300 rough points, each stopped by the 0.5 s
# budget, keeps it running for minutes, so the signals below arrive mid-run (the planned main job takes about 20 s
# with one worker since solver ehl-2026.11-11 and could finish first)
MAIN_JOB = ["pipeline", "quick", "--workers", "1", "--effects", "full", "--time-limit-s", "0.5", "--progress", "log"]
MAIN_DIR = "gearloss_quick_fast_full"


def _env():
    return {**os.environ, "PYTHONPATH": str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", "")}


def _default_signals():
    """The child handles SIGINT as a terminal's Ctrl-C would arrive (a parent started in the background may have
    it ignored, which the child would inherit)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def run(argv, cwd, timeout=300):
    return subprocess.run([sys.executable, "-m", "workflows.cli", *argv], cwd=cwd, capture_output=True, text=True,
                          timeout=timeout, env=_env(), preexec_fn=_default_signals)


def interrupt(argv, cwd, *, after_s: float, wait_for: str, sig=signal.SIGINT, timeout=240):
    """Start ``gearloss argv``, wait for ``wait_for`` on stderr, then ``after_s`` seconds, send ``sig``; return
    (exit code, stderr)."""
    proc = subprocess.Popen([sys.executable, "-m", "workflows.cli", *argv], cwd=cwd, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=_env(), preexec_fn=_default_signals)
    err, started = "", time.monotonic()
    try:
        while wait_for not in err:
            assert time.monotonic() - started < timeout, f"no {wait_for!r} on stderr: {err}"
            ready, _, _ = select.select([proc.stderr], [], [], 1.0)
            if ready:
                line = proc.stderr.readline()
                assert line or proc.poll() is None, f"ended early ({proc.poll()}): {err}"
                err += line
        time.sleep(after_s)
        proc.send_signal(sig)
        out, rest = proc.communicate(timeout=timeout)
    finally:
        if proc.poll() is None:
            proc.kill()
    return proc.returncode, err + rest


@pytest.mark.slow
def test_main_job_smoke_and_main_job_again_in_any_order_without_collisions(tmp_path):
    # smoke first
    first_smoke = run(["pipeline", "smoke", "--workers", "1", "--progress", "none"], tmp_path)
    assert first_smoke.returncode == 0, first_smoke.stderr
    assert first_smoke.stdout.startswith("SMOKE RUN")
    # the main job, interrupted: exit 130 and the command that resumes it
    code, err = interrupt(MAIN_JOB, tmp_path, after_s=6.0, wait_for="resume with:")
    assert code == 130, err
    resume_line = [line for line in err.splitlines() if "interrupted by SIGINT" in line]
    assert resume_line and resume_line[-1].endswith("resume with: gearloss " + " ".join(MAIN_JOB)), err
    quick = tmp_path / MAIN_DIR / "dataset.h5"
    assert read_metadata(quick)["factorial"]["name"] == "quick"
    done = read_metadata(quick)["counts"]["ok"]
    assert done >= 1
    # the smoke pipeline again: its own directory, nothing recomputed, the main job's file untouched
    again = run(["pipeline", "quick", "--factorial", "smoke", "--workers", "1", "--progress", "none", "--json"],
                tmp_path)
    assert again.returncode == 0, again.stderr
    assert '"computed": 0' in again.stdout and "resuming: 96 of 96 points done" in again.stderr
    assert read_metadata(tmp_path / "gearloss_smoke_fast_smooth" / "dataset.h5")["factorial"]["name"] == "smoke"
    assert read_metadata(quick)["counts"]["ok"] == done
    # the main job again: it resumes from the points done; stopped by SIGTERM this time: exit 143, resume command
    code, err = interrupt(MAIN_JOB, tmp_path, after_s=1.0, wait_for="resume with:", sig=signal.SIGTERM)
    assert code == 143, err
    assert f"resuming: {done} of 324 points done" in err
    assert "interrupted by SIGTERM; finished work is kept, resume with: gearloss pipeline quick" in err
    assert read_metadata(quick)["counts"]["ok"] >= done
    assert sorted(p.name for p in tmp_path.iterdir()) == [MAIN_DIR, "gearloss_smoke_fast_smooth"]


def _handles_sigterm(pid: int, timeout: float = 60.0) -> None:
    """Wait until the process catches SIGTERM (gearloss's main has installed its handler: imports are done)."""
    status = Path(f"/proc/{pid}/status")
    started = time.monotonic()
    while time.monotonic() - started < timeout:
        if not status.exists():
            time.sleep(5.0)  # no /proc: give the imports time
            return
        caught = next((line.split()[1] for line in status.read_text().splitlines() if line.startswith("SigCgt")), "0")
        if int(caught, 16) & (1 << (signal.SIGTERM - 1)):
            return
        time.sleep(0.1)


@pytest.mark.slow
@pytest.mark.parametrize("sig, code, words", [(signal.SIGINT, 130, "interrupted by SIGINT"),
                                              (signal.SIGTERM, 143, "terminated by SIGTERM")])
def test_ctrl_c_and_sigterm_of_a_command_outside_the_runner(tmp_path, sig, code, words):
    """A long gear sweep stopped by Ctrl-C exits 130, by SIGTERM 143, with one line saying so."""
    argv = ["gear", "sweep", "--friction", "xu2007"]
    proc = subprocess.Popen([sys.executable, "-m", "workflows.cli", *argv], cwd=tmp_path, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=_env(), preexec_fn=_default_signals)
    _handles_sigterm(proc.pid)
    time.sleep(1.0)
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == code, err
    assert err.strip() == f"gearloss: {words}: gearloss gear sweep --friction xu2007 stopped"
