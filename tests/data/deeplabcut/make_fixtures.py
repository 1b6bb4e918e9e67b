#!/usr/bin/env python3
"""Writes the DeepLabCut-style fixtures of this directory with pandas + PyTables (README.md).

DeepLabCut stores tracks as a pandas DataFrame with column MultiIndex (scorer, [individuals,] bodyparts,
coords) and an integer frame index, saved with df.to_hdf(path, "df_with_missing", format="table", mode="w")
and df.to_csv(path). This script writes the same layouts from fixed numbers (no randomness), so the .h5 and
the .csv of each layout hold identical data.
"""
import pickle
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
SCORER = "DLC_resnet50_whiskerNov23shuffle1_1000"
BODYPARTS = ["base", "mid", "tip"]


def keypoints(frames, offset_px):
    """x, y, likelihood of three keypoints along a bent whisker per frame (exact binary fractions)."""
    rows = []
    for f in frames:
        row = []
        for k, _ in enumerate(BODYPARTS):
            row += [100.0 + offset_px + 40.0 * k + 0.5 * f, 200.0 - 0.25 * k * k * 8 + 0.125 * f, 1.0 - 0.0625 * k]
        rows.append(row)
    return np.array(rows)


def single_animal():
    frames = [0, 1, 2, 4, 5]  # frame 3 was not analysed
    data = keypoints(frames, 0.0)
    data[1, 6:9] = np.nan  # tip lost in frame 1
    data[2, 5] = 0.03125  # low-likelihood mid point in frame 2
    cols = pd.MultiIndex.from_product([[SCORER], BODYPARTS, ["x", "y", "likelihood"]],
                                      names=["scorer", "bodyparts", "coords"])
    return pd.DataFrame(data, columns=cols, index=frames)


def multi_animal():
    frames = [0, 1, 2]
    data = np.hstack([keypoints(frames, 0.0), keypoints(frames, 300.0)])
    data[0, 9:12] = np.nan  # mouse2's base untracked in frame 0
    cols = pd.MultiIndex.from_product([[SCORER], ["mouse1", "mouse2"], BODYPARTS, ["x", "y", "likelihood"]],
                                      names=["scorer", "individuals", "bodyparts", "coords"])
    return pd.DataFrame(data, columns=cols, index=frames)


def main():
    for name, df in [("single_animal", single_animal()), ("multi_animal", multi_animal())]:
        df.to_hdf(HERE / f"{name}.h5", key="df_with_missing", format="table", mode="w")
        df.to_csv(HERE / f"{name}.csv")
        # Small seeds for the fuzz harness (fuzz/corpus/dlc_h5, under libFuzzer's -max_len): the same table
        # deflated and without PyTables' index.
        df.to_hdf(HERE.parents[2] / "fuzz" / "corpus" / "dlc_h5" / f"{name}_zlib.h5", key="df_with_missing",
                  format="table", mode="w", index=False, complevel=9, complib="zlib")
    # pandas' "fixed" format (DeepLabCut's labelled-data files): not a table, rejected by the reader.
    single_animal().to_hdf(HERE / "fixed_format.h5", key="df_with_missing", mode="w")
    # The column labels pickled with every protocol (the decoder's tests and fuzz seeds).
    labels = [(1, list(multi_animal().columns[:4]))]
    for protocol in range(0, 6):
        (HERE / f"labels_protocol{protocol}.pickle").write_bytes(pickle.dumps(labels, protocol))
    print(f"pandas {pd.__version__}, PyTables {__import__('tables').__version__}, Python {sys.version.split()[0]}")


if __name__ == "__main__":
    main()
