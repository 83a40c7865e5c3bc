"""The command line, run as a user would: through the installed console script."""

import json
import math
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest
from reference_points import JARM, JARM_ARGS, JARM_BODY_ARGS, SLIP_FIRST_ARGS

import eccjump
from eccjump import roll
from eccjump.cli import main


def run(*args: str) -> subprocess.CompletedProcess:
    # The script installed with this interpreter's eccjump, not whichever `eccjump` is first on
    # PATH (that may belong to another installation); without one, the module.
    exe = Path(sysconfig.get_path("scripts")) / (
        "eccjump.exe" if sys.platform == "win32" else "eccjump"
    )
    cmd = [str(exe), *args] if exe.is_file() else [sys.executable, "-m", "eccjump.cli", *args]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=120, check=False)


def test_roll_table_names_the_event_and_the_angle():
    p = run("roll", *JARM_ARGS, "--mu-s", "1")
    assert p.returncode == 0, p.stderr
    assert "terminal event: liftoff" in p.stdout
    assert "334.34383" in p.stdout


def test_roll_json_is_machine_readable():
    p = run("roll", *SLIP_FIRST_ARGS, "--mu-s", "1", "--json")
    data = json.loads(p.stdout)
    assert data["terminal_event"] == "slip"
    assert data["theta_deg"] == pytest.approx(316.4716772, abs=1e-6)
    assert data["events"][0]["name"] == "slip"


def test_roll_takes_the_integrator_and_records_it(capsys):
    args = ["roll", *JARM_ARGS, "--mu-s", "1", "--json"]
    assert main([*args, "--integrator", "DOP853"]) == 0
    data = json.loads(capsys.readouterr().out)
    ref = roll(*JARM, mu_s=1.0, integrator="DOP853")
    assert data["integrator"] == "DOP853" and data["nfev"] == ref.nfev
    assert data["theta_deg"] == math.degrees(ref.theta[-1])
    assert main(args) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["integrator"] == "RK45" and data["nfev"] != ref.nfev
    with pytest.raises(SystemExit):
        main([*args, "--integrator", "RK4"])
    assert "--integrator" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--alpha", "100", "--chi", "0.1", "--km", "0.1"], "[0, 90]"),
        (["--alpha", "10", "--chi", "0.5", "--km", "0.6"], "km = 0.6"),
    ],
)
def test_bad_input_is_a_clear_error(args, message, capsys):
    with pytest.raises(SystemExit) if "100" in args else _no_exit():
        code = main(["roll", *args])
        assert code == 2
    assert message in capsys.readouterr().err


class _no_exit:
    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False


def test_version(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["--version"])
    assert exit_.value.code == 0
    assert capsys.readouterr().out.strip() == f"eccjump {eccjump.__version__}"


@pytest.mark.slow
@pytest.mark.parametrize("command", ["roll", "simulate"])
def test_an_alpha_that_looks_like_radians_gets_a_hint(command):
    """The command line takes degrees, Python radians: --alpha 0.7 runs at 0.7 deg and says
    how to write 0.7 rad; --alpha 40 says nothing."""
    body = (*JARM_BODY_ARGS, "--mu-s", "1")
    small = run(command, *body, "--alpha", "0.7")
    assert small.returncode == 0 and "for 0.7 rad write --alpha 40.107" in small.stderr
    plain = run(command, *body, "--alpha", "40")
    assert plain.returncode == 0 and "note" not in plain.stderr
