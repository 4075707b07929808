"""Build src/pas/waves/data/box_hull_capytaine.nc: Capytaine BEM of a box hull (not run in CI).

The box is the hull the built-in closed-form model (:mod:`pas.waves.ship`)
describes when ``block_coefficient = 1``: length ``L``, beam ``B``, draught
``T``, uniform mass (so the radii of gyration are those of the submerged box,
as in Jensen et al. 2004), centre of mass at the centroid of the submerged
box, motions about that point. Radiation and diffraction are solved with
Capytaine's ``BEMSolver`` (deep water, zero speed) on a lid-closed mesh (the
lid removes the irregular frequencies of a box) over a modest frequency grid
and three headings, assembled with ``assemble_dataset`` and saved with
Capytaine's NetCDF writer (complex values split in re/im), with the
inertia and hydrostatic stiffness that the RAO needs and Capytaine's own
``post_pro.rao`` as the variable ``rao`` for the loader's check.

Run in a separate environment with Capytaine (it is not a dependency of pas)::

    python -m venv /tmp/capy && /tmp/capy/bin/pip install capytaine==3.0.0 h5netcdf
    /tmp/capy/bin/python benchmarks/studies/make_box_rao.py

51 s (120 m) and 86-148 s (240 m) on the shared 2-core machine; each file is 54 kB.
The 240 m box (L/B = 12, tests/data/box_hull_240m_capytaine.nc) tests the explanation of
the difference to the built-in strip model: `--length 240 --out tests/data/...`.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

LENGTH, BEAM, DRAUGHT = 120.0, 20.0, 6.0
RHO, G = 1025.0, 9.81
OMEGA = np.concatenate([[0.05, 0.1, 0.15], np.arange(0.2, 1.61, 0.1)])
HEADINGS_DEG = (180.0, 135.0, 90.0)
PANEL = 3.0  # target panel size (m)
OUT = (
    Path(__file__).resolve().parents[2] / "src" / "pas" / "waves" / "data" / "box_hull_capytaine.nc"
)


def build_body(length, beam, draught):
    import capytaine as cpt  # not a dependency of pas: only this script needs it

    """The submerged box (top open, lid at the waterline), rigid-body dofs about the centroid."""
    resolution = tuple(int(np.ceil(d / PANEL)) for d in (length, beam, draught))
    centre = (0.0, 0.0, -draught / 2)
    mesh = cpt.mesh_parallelepiped(size=(length, beam, draught), center=centre,
                                   resolution=resolution, missing_sides={"top"}, name="box")
    body = cpt.FloatingBody(mesh=mesh, lid_mesh=mesh.generate_lid(z=0.0),
                            dofs=cpt.rigid_body_dofs(rotation_center=centre),
                            center_of_mass=centre, name="box")
    body.inertia_matrix = body.compute_rigid_body_inertia(rho=RHO)
    body.hydrostatic_stiffness = body.immersed_part().compute_hydrostatic_stiffness(rho=RHO, g=G)
    return body


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--length", type=float, default=LENGTH, help="box length (m)")
    parser.add_argument("--beam", type=float, default=BEAM, help="box beam (m)")
    parser.add_argument("--draught", type=float, default=DRAUGHT, help="box draught (m)")
    parser.add_argument("--out", type=Path, default=OUT, help="NetCDF file to write")
    args = parser.parse_args(argv)
    import capytaine as cpt
    from capytaine.io.xarray import save_dataset_as_netcdf
    from capytaine.post_pro import rao

    t0 = time.perf_counter()
    body = build_body(args.length, args.beam, args.draught)
    problems = []
    # Same k L at every node for any length (Froude scaling of the 120 m grid),
    # so boxes of different slenderness compare node by node.
    for w in OMEGA * np.sqrt(LENGTH / args.length):
        problems += [cpt.RadiationProblem(body=body, radiating_dof=dof, omega=w, rho=RHO, g=G)
                     for dof in body.dofs]
        problems += [cpt.DiffractionProblem(body=body, wave_direction=np.deg2rad(b), omega=w,
                                            rho=RHO, g=G) for b in HEADINGS_DEG]
    solver = cpt.BEMSolver()
    results = solver.solve_all(problems, progress_bar=False)
    ds = cpt.assemble_dataset(results, hydrostatics=False)
    ds["inertia_matrix"] = body.inertia_matrix
    ds["hydrostatic_stiffness"] = body.hydrostatic_stiffness
    ds["rao"] = rao(ds)
    ds.attrs.update(
        {
            "title": (
                "Capytaine radiation/diffraction of a box hull "
                "(pas benchmarks/studies/make_box_rao.py)"
            ),
            "length": args.length,
            "beam": args.beam,
            "draught": args.draught,
            "rotation_center_x": 0.0,
            "rotation_center_y": 0.0,
            "rotation_center_z": -args.draught / 2,
            "capytaine_version": cpt.__version__,
            "time_convention": (
                "Capytaine: Re[X exp(-i omega t)], "
                "incident eta = Re[exp(i k (x cos b + y sin b) - i omega t)]"
            ),
            "n_panels": int(body.mesh.nb_faces),
            "n_lid_panels": int(body.lid_mesh.nb_faces),
        }
    )
    for name in ("body_name", "rho", "g", "water_depth", "forward_speed", "free_surface"):
        if name in ds.coords and ds.coords[name].size == 1:
            ds.attrs[name] = (
                ds.coords[name].values.item()
                if name != "body_name"
                else str(ds.coords[name].values)
            )
    drop = [
        c for c in ds.coords if c not in ds.dims and c not in ("radiating_dof", "influenced_dof")
    ]
    ds = ds.drop_vars(drop)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    save_dataset_as_netcdf(args.out, ds)
    print(
        f"{args.out}: {args.out.stat().st_size / 1e3:.0f} kB, {len(problems)} problems, "
        f"{body.mesh.nb_faces} + {body.lid_mesh.nb_faces} panels, {time.perf_counter() - t0:.0f} s"
    )


if __name__ == "__main__":
    main()
