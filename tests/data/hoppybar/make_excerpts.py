"""Regenerate the test-data copies in this folder from the HopPyBar example data.

Source: LANL HopPyBar (https://github.com/lanl/HopPyBar, BSD-3-Clause, see LICENSE here), as
provided at ``../shared/data/hoppybar`` next to the project root.

* ``LANLstandard-Cu/20061201_1148HE_CuOFE_273K.raw``: full copy (112 KB), unchanged.
* ``mini-Kolsky-PMMA-13/PMMA_13_Input.dat``: full copy, unchanged.
* ``mini-Kolsky-PMMA-13/180303_171828_Ch1.csv`` and ``..._Ch2.csv``: the samples with
  -20 us <= t < 100 us (15000 of 50000, full 125 MS/s resolution; incident pulse at 0-10 us,
  reflected pulse at 40-50 us, its echo from the impact end at 80-90 us). Data lines are copied
  verbatim; in the header block the values of "Record Length" (15000), "Trigger Point" (2500)
  and "Horizontal Offset" (-2e-5 s) are rewritten to describe the excerpt.
* ``mini-Kolsky-PMMA-13/180303_171828_Ch3.csv`` and ``..._Ch4.csv`` (opposite gauges on the
  transmitted bar): every 5th sample with -20 us <= t < 70 us (2250 of 50000, 40 ns apart;
  transmitted pulse at 42-54 us), kept small for the repository. The kept data lines are copied
  verbatim; "Record Length" (2250), "Sample Interval" (4e-8 s), "Trigger Point" (500) and
  "Horizontal Offset" (-2e-5 s) are rewritten. No filtering: the samples are picked, not averaged.

Run: ``python tests/data/hoppybar/make_excerpts.py [path/to/shared/data/hoppybar]``.
"""

import shutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
START, STOP = 7500, 22500  # sample indices of -20 us and 100 us (t = -80 us + k * 8 ns)
NEW_HEADER = {"Record Length": "15000", "Trigger Point": "2500", "Horizontal Offset": "-2.00000000e-005"}
# the transmitted bar's channels: -20 us <= t < 70 us, every 5th sample (40 ns)
STOP_T, STEP_T = 18750, 5
NEW_HEADER_T = {"Record Length": "2250", "Sample Interval": "4.00000000e-008", "Trigger Point": "500",
                "Horizontal Offset": "-2.00000000e-005"}


def excerpt_tektronix(src: Path, dst: Path, stop: int = STOP, step: int = 1,
                      header: dict[str, str] = NEW_HEADER) -> None:
    """Copy the data lines ``START:stop:step`` of ``src`` to ``dst`` verbatim (time and value columns), with the
    header block's fields named in ``header`` rewritten to describe the excerpt."""
    lines = src.read_text(encoding="ascii").splitlines()
    out = []
    for i, line in enumerate(lines[START:stop:step]):
        values = line.split(",", 3)[3]
        if i < 6:  # the header block: name, value, unit in the first three columns
            fields = lines[i].split(",")[:3]
            key = fields[0].strip('"')
            if key in header:
                fields[1] = header[key]
            prefix = ",".join(fields)
        else:
            prefix = ",,"
        out.append(prefix + "," + values)
    dst.write_bytes(("\r\n".join(out) + "\r\n").encode("ascii"))


def main(shared: Path) -> None:
    shutil.copy(shared / "LICENSE", HERE / "LICENSE")
    (HERE / "LANLstandard-Cu").mkdir(exist_ok=True)
    shutil.copy(shared / "LANLstandard-Cu" / "20061201_1148HE_CuOFE_273K.raw", HERE / "LANLstandard-Cu")
    mini_src = shared / "mini-Kolsky-PMMA-13"
    mini_dst = HERE / "mini-Kolsky-PMMA-13"
    mini_dst.mkdir(exist_ok=True)
    shutil.copy(mini_src / "PMMA_13_Input.dat", mini_dst)
    for ch in ("Ch1", "Ch2"):
        excerpt_tektronix(mini_src / f"180303_171828_{ch}.csv", mini_dst / f"180303_171828_{ch}.csv")
    for ch in ("Ch3", "Ch4"):
        excerpt_tektronix(mini_src / f"180303_171828_{ch}.csv", mini_dst / f"180303_171828_{ch}.csv", STOP_T,
                          STEP_T, NEW_HEADER_T)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else HERE.parents[2].parent / "shared" / "data" / "hoppybar")
