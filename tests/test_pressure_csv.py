"""Unit tests of crankbalance.io.pressure_csv: the cylinder-pressure table reader."""

from __future__ import annotations

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.io import pressure_csv
from crankbalance.io.pressure_csv import read_pressure_csv


def _table(tmp_path, text: str, name: str = "p.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_reads_degrees_and_bar_as_radians_and_pascal(tmp_path):
    angle = np.arange(-360, 360, 10.0)
    bar = 1.0 + 40.0 * np.exp(-(((angle - 10) / 30) ** 2))
    text = "angle_deg,pressure_bar\n" + "\n".join(
        f"{a},{p}" for a, p in zip(angle, bar, strict=True)
    )
    rad, pa = read_pressure_csv(_table(tmp_path, text))
    # the conversion of the former CLI reader, bit for bit
    assert np.array_equal(rad, np.radians(angle))
    assert np.array_equal(pa, bar * 1e5)


def test_comments_blank_lines_and_no_header(tmp_path):
    text = "# measured\n\n0, 1.0\n90, 2.0  # note\n180,3.0\n\n270,4.0\n"
    rad, pa = read_pressure_csv(str(_table(tmp_path, text)))
    assert rad.tolist() == pytest.approx([0, np.pi / 2, np.pi, 1.5 * np.pi])
    assert pa.tolist() == [1e5, 2e5, 3e5, 4e5]


@pytest.mark.parametrize(
    "text, needle",
    [
        ("a,b\n0,1\n1,x\n2,3\n3,4\n", "line 3, pressure_bar"),
        ("0,1\n1,2\n2,nan\n3,4\n", "line 3, pressure_bar"),
        ("0,1,2\n1,2,3\n", "two comma-separated columns"),
        ("0;1\n1;2\n2;3\n3;4\n", "two comma-separated columns"),
        ("angle,pressure\n0,1\n1,2\n", "at least 4 rows"),
        ("", "at least 4 rows"),
    ],
)
def test_bad_tables_name_the_file_line_and_what_is_allowed(tmp_path, text, needle):
    path = _table(tmp_path, text)
    with pytest.raises(InputError, match=needle) as error:
        read_pressure_csv(path)
    assert str(path) in str(error.value)


def test_refuses_large_binary_missing_and_folders(tmp_path, monkeypatch):
    big = _table(tmp_path, "0,1\n" * 40, "big.csv")
    monkeypatch.setattr(pressure_csv, "MAX_FILE_BYTES", 100)
    with pytest.raises(InputError, match="larger than 100 bytes") as error:
        read_pressure_csv(big)
    assert error.value.field == "pressure_csv" and error.value.value == str(big)
    monkeypatch.undo()
    binary = tmp_path / "b.csv"
    binary.write_bytes(b"0,1\x00\n")
    with pytest.raises(InputError, match="binary"):
        read_pressure_csv(binary)
    latin = tmp_path / "l.csv"
    latin.write_bytes("0,1\n1,2\n2,3\n3,4 # \xe9\n".encode("latin-1"))
    with pytest.raises(InputError, match="UTF-8"):
        read_pressure_csv(latin)
    with pytest.raises(InputError, match="cannot be read"):
        read_pressure_csv(tmp_path / "missing.csv")
    with pytest.raises(InputError, match="folder"):
        read_pressure_csv(tmp_path)
