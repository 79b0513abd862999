#!/usr/bin/env python3
"""A simple scene-flow method for patchflow data, in numpy only: ego-motion compensated nearest
neighbour. Each point of sweep k is matched to the nearest point of sweep k-1 (both in the world
frame of the ego's own pose estimate); the displacement over the sweep interval is its velocity.
Ground points and matches too short to tell from sampling stand still. The predictions are
written in the layout `patchflow flow` writes, for `patchflow score`:

    PRED/sequences/<name>/flow/NNNNNN.bin    float32 vx, vy, vz per point, world frame, m/s
    PRED/sequences/<name>/moving/NNNNNN.bin  uint8 per point, 1 = moving

Usage (see docs/scoring.md):

    python3 examples/python/nearest_neighbour_flow.py DATA_DIR PRED_DIR
    patchflow score --data DATA_DIR --predictions PRED_DIR=NN-FLOW --out results/score-nn
"""

import argparse
import pathlib
import sys

import numpy as np

CELL_M = 1.5          # hash grid cell for the neighbour search (x, y): one match radius
MAX_MATCH_M = 1.5     # a farther nearest neighbour is no match (a car at 15 m/s moves 1.5 m)
MIN_MOTION_M = 0.12   # shorter displacements are sampling noise: the point stands still
GROUND_Z_M = -1.45    # sensor-frame height below which a point is ground (sensor at 1.73 m)
MOVING_MPS = 1.0      # the moving mask's speed threshold


def read_poses(path):
    """KITTI poses: 12 floats a line, row-major 3x4 world_from_sensor."""
    rows = np.loadtxt(path, dtype=np.float64).reshape(-1, 3, 4)
    poses = np.tile(np.eye(4), (len(rows), 1, 1))
    poses[:, :3, :] = rows
    return poses


def read_points(path):
    return np.fromfile(path, dtype=np.float32).reshape(-1, 4)[:, :3].astype(np.float64)


def to_world(points, pose):
    return points @ pose[:3, :3].T + pose[:3, 3]


def nearest(previous, queries):
    """Index of and distance to each query's nearest previous point within MAX_MATCH_M
    (index -1 where none), by hashing the previous points on an x-y grid."""
    cells = np.floor(previous[:, :2] / CELL_M).astype(np.int64)
    order = np.lexsort((cells[:, 1], cells[:, 0]))
    cells, sorted_points = cells[order], previous[order]
    keys, starts, counts = np.unique(cells, axis=0, return_index=True, return_counts=True)
    table = {(int(k[0]), int(k[1])): (s, c) for k, s, c in zip(keys, starts, counts)}
    query_cells = np.floor(queries[:, :2] / CELL_M).astype(np.int64)
    best = np.full(len(queries), -1, dtype=np.int64)
    best_d = np.full(len(queries), np.inf)
    reach = int(np.ceil(MAX_MATCH_M / CELL_M))
    unique_cells, inverse = np.unique(query_cells, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    members = np.argsort(inverse, kind="stable")
    bounds = np.searchsorted(inverse[members], np.arange(len(unique_cells) + 1))
    for u, (cx, cy) in enumerate(unique_cells):
        q = members[bounds[u]:bounds[u + 1]]
        candidates = [np.arange(s, s + c) for dx in range(-reach, reach + 1)
                      for dy in range(-reach, reach + 1)
                      for s, c in [table.get((int(cx) + dx, int(cy) + dy), (0, 0))] if c]
        if not candidates:
            continue
        idx = np.concatenate(candidates)
        d = np.linalg.norm(queries[q, None, :] - sorted_points[None, idx, :], axis=2)
        j = np.argmin(d, axis=1)
        best_d[q] = d[np.arange(len(q)), j]
        best[q] = order[idx[j]]
    best[best_d > MAX_MATCH_M] = -1
    return best


def sequence_flow(seq_dir, out_dir):
    poses_file = seq_dir / "poses_estimated.txt"
    poses = read_poses(poses_file if poses_file.exists() else seq_dir / "poses.txt")
    times = np.loadtxt(seq_dir / "times.txt", dtype=np.float64).reshape(-1)
    sweeps = sorted((seq_dir / "velodyne").glob("*.bin"))
    (out_dir / "flow").mkdir(parents=True, exist_ok=True)
    (out_dir / "moving").mkdir(parents=True, exist_ok=True)
    previous_world = None
    for k, path in enumerate(sweeps):
        points = read_points(path)
        world = to_world(points, poses[k])
        velocity = np.zeros_like(world)
        if previous_world is None:
            velocity[:] = np.nan  # the first sweep has no predecessor
        else:
            dt = times[k] - times[k - 1]
            above = points[:, 2] > GROUND_Z_M
            match = nearest(previous_world, world[above])
            rows = np.flatnonzero(above)[match >= 0]
            displacement = world[rows] - previous_world[match[match >= 0]]
            displacement[np.linalg.norm(displacement, axis=1) < MIN_MOTION_M] = 0.0
            velocity[rows] = displacement / dt
        speed = np.linalg.norm(np.nan_to_num(velocity), axis=1)
        velocity.astype(np.float32).tofile(out_dir / "flow" / path.name)
        (speed > MOVING_MPS).astype(np.uint8).tofile(out_dir / "moving" / path.name)
        previous_world = world
    return len(sweeps)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("data", type=pathlib.Path, help="a dataset written by patchflow generate")
    parser.add_argument("out", type=pathlib.Path, help="prediction folder to write")
    args = parser.parse_args()
    sequences = sorted(p for p in (args.data / "sequences").iterdir() if (p / "velodyne").is_dir())
    if not sequences:
        sys.exit(f"{args.data}: no sequences/<name>/velodyne/ here: not a patchflow dataset")
    for seq_dir in sequences:
        n = sequence_flow(seq_dir, args.out / "sequences" / seq_dir.name)
        print(f"{seq_dir.name}: {n} sweeps")


if __name__ == "__main__":
    main()
