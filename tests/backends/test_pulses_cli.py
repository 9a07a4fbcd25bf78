"""End to end: ``cncc --emit=pulses`` on examples/contour.nc, final positions rebuilt from the pulses."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from cncc.backends.pulses import read_queue
from cncc.cli import main
from cncc.machines import load_machine

ROOT = Path(__file__).resolve().parents[2]
PROGRAM = str(ROOT / "examples" / "contour.nc")
G54_MM = (100.0, 50.0, -150.0)  # keeps the program inside generic-mill's soft limits
# contour.nc starts at the program origin and ends at X0 Y0 Z10 (N004 ... N012 G00 Z10.0)
START_MM = np.array(G54_MM)
END_MM = np.array(G54_MM) + np.array([0.0, 0.0, 10.0])
# travel per axis (mm): X 0-20-55, arc 55-45, 45-0; Y 0-38-45, 45-10, arc 10-0; Z 0-10, 10 - -10, -10-10
TRAVEL_MM = np.array([20 + 35 + 10 + 45, 38 + 7 + 35 + 10, 10 + 20 + 20], dtype=np.float64)


@pytest.fixture()
def offsets(tmp_path: Path) -> str:
    path = tmp_path / "offsets.toml"
    x, y, z = G54_MM
    path.write_text(f'units = "mm"\n[work.G54]\nX = {x}\nY = {y}\nZ = {z}\n', encoding="ascii")
    return str(path)


def steps_per_mm() -> np.ndarray:
    m = load_machine("generic-mill")
    return np.array([m.axis(a).step.steps_per_mm for a in "XYZ"])  # type: ignore[union-attr]


def expected_net_steps() -> np.ndarray:
    r = steps_per_mm()
    net: np.ndarray = np.floor(END_MM * r + 0.5) - np.floor(START_MM * r + 0.5)
    return net


def test_npz_file_rebuilds_the_end_point(tmp_path: Path, offsets: str) -> None:
    out = tmp_path / "contour.npz"
    rc = main(["--emit=pulses", "--pulse-format=npz", "--offsets", offsets, "-o", str(out), PROGRAM])
    assert rc == 0
    z = np.load(out)
    assert list(z["axes"][:3]) == ["X", "Y", "Z"]
    net = np.array([int(z[f"{a}_dir"].astype(np.int64).sum()) for a in "XYZ"])
    count = np.array([z[f"{a}_dir"].size for a in "XYZ"])
    np.testing.assert_array_equal(net, expected_net_steps())
    # every move is monotone per axis, so each axis makes exactly its travel in steps
    np.testing.assert_array_equal(count, np.rint(TRAVEL_MM * steps_per_mm()))
    for a in "XYZ":
        assert np.all(np.diff(z[f"{a}_t_ns"]) > 0)
        assert not z[f"{a}_backlash"].any()  # generic-mill has no backlash


def test_queue_on_stdout_rebuilds_the_end_point(capsys: pytest.CaptureFixture[str], offsets: str) -> None:
    rc = main(["--emit=pulses", "--pulse-format=queue", "--pulse-mode=interp", "--offsets", offsets, PROGRAM])
    assert rc == 0
    decoded = read_queue(capsys.readouterr().out.splitlines())
    net = np.array([int(np.where(decoded[a][1] == 1, 1, -1).sum()) for a in "XYZ"])
    np.testing.assert_array_equal(net, expected_net_steps())


def test_vcd_on_stdout(capsys: pytest.CaptureFixture[str], offsets: str) -> None:
    assert main(["--emit=pulses", "--offsets", offsets, PROGRAM]) == 0
    out = capsys.readouterr().out
    assert out.startswith("$comment")
    rises = sum(1 for line in out.splitlines() if line == "1!")  # X_step is identifier '!'
    assert rises == int(np.rint(TRAVEL_MM[0] * steps_per_mm()[0]))


def test_npz_needs_an_output_file(capsys: pytest.CaptureFixture[str], offsets: str) -> None:
    assert main(["--emit=pulses", "--pulse-format=npz", "--offsets", offsets, PROGRAM]) == 2  # bad option: exit 2
    cap = capsys.readouterr()
    assert cap.out == ""
    assert "error: --pulse-format=npz is binary: name the output file with -o FILE [E0904]" in cap.err


def test_no_file_is_left_when_the_program_breaks_a_limit(tmp_path: Path, capsys: pytest.CaptureFixture[str]
                                                         ) -> None:
    out = tmp_path / "contour.csv"
    # without offsets Z10 is above generic-mill's soft limit (Z max 1 mm)
    assert main(["--emit=pulses", "--pulse-format=csv", "-o", str(out), PROGRAM]) == 1
    assert "error: axis Z" in capsys.readouterr().err
    assert not out.exists()
    assert list(tmp_path.iterdir()) == []
