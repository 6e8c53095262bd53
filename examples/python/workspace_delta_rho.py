#!/usr/bin/env python3
"""A workspace map of the error amplification δρ (Smirnov 2019, §5.2.2, eqs. 144–146: mm of tool-point error per mm of
equal actuator errors) over a plane section of the ch5 hexapod, from one batch call of Machine.conditioning.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/workspace_delta_rho.py --out out/ [--quick]
        [--machine examples/machines/hexapod_ch5.yaml] [--z-mm 700] [--range-mm 400]

The section is the level platform (angles 0) at height z, x and y within ±range of the home point. Points whose
struts leave the machine's actuator range (batch IK with errors="nan") are left blank. Writes
workspace_delta_rho.png and workspace_delta_rho.json and prints δρ at home, its range and the share of the
section within the drives' range.
"""

import time

import numpy as np

from example_support import REPOSITORY, arguments, import_pkm, pyplot, write_outputs

pkm = import_pkm()


def options(parser):
    parser.add_argument("--machine", default=str(REPOSITORY / "examples/machines/hexapod_ch5.yaml"))
    parser.add_argument("--z-mm", type=float, default=None, help="height of the section (default: home's z)")
    parser.add_argument("--range-mm", type=float, default=400.0, help="half-width of the section around home")


def main():
    args = arguments(__doc__.splitlines()[0], sweep=False, extra=options)
    machine = pkm.Machine.load(args.machine)
    home = np.asarray(machine.home, dtype=float)
    z_mm = home[2] if args.z_mm is None else args.z_mm
    count = 41 if args.quick else 401
    xs = home[0] + np.linspace(-args.range_mm, args.range_mm, count)
    ys = home[1] + np.linspace(-args.range_mm, args.range_mm, count)
    grid_x, grid_y = np.meshgrid(xs, ys)  # rows: y, columns: x
    poses = np.zeros((grid_x.size, 6))
    poses[:, 0], poses[:, 1], poses[:, 2] = grid_x.ravel(), grid_y.ravel(), z_mm

    started = time.perf_counter()
    measures = machine.conditioning(poses)
    in_range = np.isfinite(machine.ik(poses, errors="nan")).all(axis=1)
    seconds = time.perf_counter() - started
    delta_rho = np.where(in_range, measures["delta_rho"], np.nan).reshape(grid_x.shape)
    at_home = float(machine.conditioning(np.array([home[0], home[1], z_mm, 0.0, 0.0, 0.0]))["delta_rho"])

    finite = np.isfinite(delta_rho)
    lowest = np.unravel_index(np.nanargmin(delta_rho), delta_rho.shape)
    summary = {"machine": args.machine, "z_mm": float(z_mm), "points": int(delta_rho.size),
               "in_range_share": float(finite.mean()), "delta_rho_at_centre": at_home,
               "delta_rho_min": float(np.nanmin(delta_rho)), "delta_rho_max": float(np.nanmax(delta_rho)),
               "min_at_mm": [float(grid_x[lowest]), float(grid_y[lowest])],
               "batch_seconds": seconds}
    print(f"{machine.name}: {delta_rho.size} poses at z = {z_mm:g} mm in {seconds * 1e3:.1f} ms "
          f"(conditioning + IK, {delta_rho.size / seconds / 1e6:.2f} M poses/s)")
    print(f"δρ at the centre {at_home:.4f}; over the {finite.mean():.1%} within the drives' range "
          f"{summary['delta_rho_min']:.4f} (at x {summary['min_at_mm'][0]:.0f}, y {summary['min_at_mm'][1]:.0f}) "
          f"… {summary['delta_rho_max']:.4f} mm/mm")

    plt = pyplot()
    figure, axes = plt.subplots(figsize=(7, 6))
    image = axes.pcolormesh(grid_x, grid_y, delta_rho, shading="auto", cmap="viridis")
    figure.colorbar(image, ax=axes, label="δρ (mm of tool point per mm of actuator error)")
    if finite.sum() > 3 and np.nanmax(delta_rho) > np.nanmin(delta_rho):
        lines = axes.contour(grid_x, grid_y, delta_rho, levels=8, colors="white", linewidths=0.6)
        axes.clabel(lines, fontsize=7, fmt="%.2f")
    axes.plot(*summary["min_at_mm"], "r+", markersize=12, label="lowest δρ")
    axes.set_aspect("equal")
    axes.set_xlabel("x (mm)")
    axes.set_ylabel("y (mm)")
    axes.set_title(f"{machine.name}: δρ at z = {z_mm:g} mm, platform level\n(blank: a strut beyond its range)")
    axes.legend(loc="upper right")
    write_outputs(args.out, "workspace_delta_rho", figure, summary)


if __name__ == "__main__":
    main()
