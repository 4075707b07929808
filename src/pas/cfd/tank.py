"""An example OpenFOAM case: a 2D wave tank with a fixed bow, a deck and a deckhouse wall.

Green water is the load: waves from the inlet run up the wall-sided bow,
overtop the deck (``freeboard`` above the still water) and hit the deckhouse
wall at the end of the deck.  The structure is a fixed, bottom-standing
block — a plain stand-in for a ship's bow, so that the case meshes with
``blockMesh`` alone — and the tank is one cell thick (forces per metre of
breadth).  :meth:`GreenWaterTank.write` writes the whole case folder (mesh,
fields, solver settings, the ``forces`` and wave-gauge function objects); an
event's waves (``constant/waveProperties``) and run times (``system/pasEvent``)
are written per event by :class:`~pas.cfd.oracle.OpenFOAMOracle`.

For your own case, keep what the oracle needs (see the guide page "PAS with
OpenFOAM"): an inlet patch with ``waveVelocity``/``waveAlpha``, a
``#include "pasEvent"`` line in ``system/controlDict`` after ``endTime``, and a
``forces`` function object per load.
"""

from __future__ import annotations

import math
import os
import shutil
from dataclasses import dataclass

__all__ = ["GreenWaterTank"]

HEADER = ("FoamFile\n{{\n    version 2.0;\n    format ascii;\n    class {cls};\n"
          "    object {obj};\n}}\n")


def _foam(path, cls, obj, body):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(HEADER.format(cls=cls, obj=obj) + body)


@dataclass(frozen=True)
class GreenWaterTank:
    """Geometry and mesh of the example green-water case (full scale, metres).

    Attributes
    ----------
    depth : float, default 40
        Water depth.
    freeboard : float, default 8
        Deck height above the still water.
    upwave : float, default 50
        Inlet to bow distance.
    deck : float, default 20
        Bow to deckhouse wall distance.
    top : float, default 30
        Height of the tank's top (and of the deckhouse wall) above the still water;
        cells keep the size ``cell`` up to ``air`` above the deck, then grow.
    air : float, default 10
        Height above the deck up to which cells keep the size ``cell``.
    cell : float, default 0.5
        Vertical cell size in the free-surface band and above the deck; the
        tank's horizontal cells are twice that, the deck's equal to it.
    band : float, default 10
        Depth below the still water down to which cells keep the size ``cell``.
    structure : bool, default True
        False: the same tank without the structure, extended ``deck + 60`` m
        beyond the bow position with an absorbing outlet, to see the incident
        waves at the bow position (event equivalence).
    max_courant : float, default 0.65
        Courant limit of the adaptive time step (flow and interface).
    """

    depth: float = 40.0
    freeboard: float = 8.0
    upwave: float = 50.0
    deck: float = 20.0
    top: float = 30.0
    cell: float = 0.5
    band: float = 10.0
    air: float = 10.0
    structure: bool = True
    max_courant: float = 0.65

    def __post_init__(self):
        for name in ("depth", "freeboard", "upwave", "deck", "top", "cell", "band", "air",
                     "max_courant"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ValueError(f"{name} must be a positive number of metres, got {v!r}")
        if self.top <= self.freeboard:
            raise ValueError(f"top ({self.top:g}) must be above freeboard ({self.freeboard:g})")
        if self.band >= self.depth:
            raise ValueError(f"band ({self.band:g}) must be less than depth ({self.depth:g})")

    # --- mesh -------------------------------------------------------------------------
    def _counts(self):
        c = self.cell
        length = self.upwave if self.structure else self.upwave + self.deck + 60.0
        nx = max(2, round(length / (2 * c)))
        nxb = max(2, round(self.deck / c))
        deep = self.depth - self.band
        coarse = min(6 * c, deep)
        nlo = max(1, math.ceil(2 * deep / (coarse + c)))
        nup = max(2, round((self.band + self.freeboard) / c))
        fine = min(self.air, self.top - self.freeboard)
        high = self.top - self.freeboard - fine
        nfine = max(2, round(fine / c))
        nhigh = math.ceil(2 * high / (coarse + c)) if high > 0 else 0
        return length, nx, nxb, nlo, nup, (nfine, nhigh), coarse

    @property
    def n_cells(self) -> int:
        """Number of cells of the mesh."""
        _, nx, nxb, nlo, nup, (nfine, nhigh), _ = self._counts()
        nair = nfine + nhigh
        return nx * (nlo + nup + nair) + (nxb * nair if self.structure else 0)

    def _block_mesh(self):
        length, nx, nxb, nlo, nup, (nfine, nhigh), coarse = self._counts()
        h, f, t = self.depth, self.freeboard, self.top
        deep = h - self.band
        zgrade = (f"(({deep / (h + f):.6g} {nlo} {self.cell / coarse:.6g}) "
                  f"({(self.band + f) / (h + f):.6g} {nup} 1))")
        nair = nfine + nhigh
        fine = min(self.air, t - f)
        agrade = "1" if not nhigh else (f"(({fine / (t - f):.6g} {nfine} 1) "
                                        f"({(t - f - fine) / (t - f):.6g} {nhigh} "
                                        f"{coarse / self.cell:.6g}))")
        xs = (0.0, length, length + self.deck)
        pts = [(xs[0], -h), (xs[1], -h), (xs[0], f), (xs[1], f), (xs[2], f),
               (xs[0], t), (xs[1], t), (xs[2], t)]
        verts = [(x, 0.0, z) for x, z in pts] + [(x, 1.0, z) for x, z in pts]
        blocks = [f"    hex (0 1 9 8 2 3 11 10) ({nx} 1 {nlo + nup}) "
                  f"simpleGrading (1 1 {zgrade})",
                  f"    hex (2 3 11 10 5 6 14 13) ({nx} 1 {nair}) simpleGrading (1 1 {agrade})"]
        patches = {"inlet": ("patch", ["(0 2 10 8)", "(2 5 13 10)"]),
                   "bottom": ("wall", ["(0 8 9 1)"]),
                   "atmosphere": ("patch", ["(5 6 14 13)"]),
                   "sides": ("empty", ["(0 1 3 2)", "(8 10 11 9)", "(2 3 6 5)",
                                       "(10 13 14 11)"])}
        if self.structure:
            blocks.append(f"    hex (3 4 12 11 6 7 15 14) ({nxb} 1 {nair}) "
                          f"simpleGrading (1 1 {agrade})")
            patches["hull"] = ("wall", ["(1 9 11 3)"])
            patches["deck"] = ("wall", ["(3 11 12 4)"])
            patches["wall"] = ("wall", ["(4 12 15 7)"])
            patches["atmosphere"][1].append("(6 7 15 14)")
            patches["sides"][1].extend(["(3 4 7 6)", "(11 14 15 12)"])
        else:
            patches["outlet"] = ("patch", ["(1 9 11 3)", "(3 11 14 6)"])
        vtext = "\n".join(f"    ({x:g} {y:g} {z:g})" for x, y, z in verts)
        ptext = "\n".join(f"    {name}\n    {{\n        type {kind};\n        faces\n        (\n"
                          + "\n".join(f"            {face}" for face in faces)
                          + "\n        );\n    }" for name, (kind, faces) in patches.items())
        return (f"scale 1;\nvertices\n(\n{vtext}\n);\nblocks\n(\n" + "\n".join(blocks)
                + f"\n);\nedges ();\nboundary\n(\n{ptext}\n);\nmergePatchPairs ();\n")

    @property
    def wall_patches(self):
        """The no-slip patches of the case."""
        return ("bottom", "hull", "deck", "wall") if self.structure else ("bottom",)

    def gauges(self):
        """Wave-gauge columns ``{name: (x, z of the lowest probe)}``: at the bow position,
        10 m in front of it, and (with the structure) 5 m onto the deck."""
        z0 = -self.band - 2.0
        g = {"bow": (self.upwave - 0.5 * self.cell, z0), "front": (self.upwave - 10.0, z0)}
        if self.structure:
            g["deck"] = (self.upwave + 5.0, self.freeboard + 0.01)
        return g

    # --- case files ----------------------------------------------------------------------
    def write(self, case):
        """Write the case folder ``case`` (created or overwritten file by file)."""
        case = os.fspath(case)
        _foam(f"{case}/system/blockMeshDict", "dictionary", "blockMeshDict", self._block_mesh())
        _foam(f"{case}/system/controlDict", "dictionary", "controlDict", self._control())
        _foam(f"{case}/system/pasEvent", "dictionary", "pasEvent",
              "endTime 20;\n")
        _foam(f"{case}/system/fvSchemes", "dictionary", "fvSchemes", FV_SCHEMES)
        _foam(f"{case}/system/fvSolution", "dictionary", "fvSolution", FV_SOLUTION)
        _foam(f"{case}/system/decomposeParDict", "dictionary", "decomposeParDict",
              "numberOfSubdomains 2;\nmethod hierarchical;\ncoeffs\n{\n    n (2 1 1);\n}\n")
        _foam(f"{case}/system/setFieldsDict", "dictionary", "setFieldsDict",
              "defaultFieldValues (volScalarFieldValue alpha.water 0);\nregions\n(\n"
              f"    boxToCell\n    {{\n        box (-1 -1 {-self.depth - 1:g}) (1e4 2 0);\n"
              "        fieldValues (volScalarFieldValue alpha.water 1);\n    }\n);\n")
        _foam(f"{case}/constant/g", "uniformDimensionedVectorField", "g",
              "dimensions [0 1 -2 0 0 0 0];\nvalue (0 0 -9.81);\n")
        _foam(f"{case}/constant/transportProperties", "dictionary", "transportProperties",
              TRANSPORT)
        _foam(f"{case}/constant/turbulenceProperties", "dictionary", "turbulenceProperties",
              "simulationType laminar;\n")
        for name, (cls, body) in self._fields().items():
            _foam(f"{case}/0.orig/{name}", cls, name, body)
        return case

    def _control(self):
        c = self.max_courant
        fo = ""
        if self.structure:
            for name, patch in (("wallForce", "wall"), ("deckForce", "deck")):
                fo += (f"    {name}\n    {{\n        type forces;\n"
                       "        libs (\"libforces.so\");\n"
                       f"        patches ({patch});\n        rho rhoInf;\n        rhoInf 1000;\n"
                       "        CofR (0 0 0);\n        writeControl timeStep;\n"
                       "        writeInterval 1;\n    }\n")
        z1 = self.top - 0.01
        for name, (x, z0) in self.gauges().items():
            n = max(2, round((z1 - z0) / (0.5 * self.cell)))
            pts = " ".join(f"({x:.4g} 0.5 {z0 + (z1 - z0) * i / (n - 1):.4g})" for i in range(n))
            fo += (f"    gauge_{name}\n    {{\n        type probes;\n"
                   "        libs (\"libsampling.so\");\n        writeControl timeStep;\n"
                   "        writeInterval 1;\n        fields (alpha.water);\n"
                   f"        probeLocations ({pts});\n    }}\n")
        return ("application interFoam;\nstartFrom startTime;\nstartTime 0;\nstopAt endTime;\n"
                "endTime 20;\n#include \"pasEvent\"\ndeltaT 0.001;\nwriteControl adjustable;\n"
                "writeInterval 1000;\npurgeWrite 0;\nwriteFormat binary;\nwritePrecision 6;\n"
                "writeCompression off;\ntimeFormat general;\ntimePrecision 6;\n"
                f"runTimeModifiable no;\nadjustTimeStep yes;\nmaxCo {c:g};\nmaxAlphaCo {c:g};\n"
                f"maxDeltaT 0.05;\nfunctions\n{{\n{fo}}}\n")

    def _fields(self):
        walls = self.wall_patches
        outlet = not self.structure

        def bf(entries):
            body = "boundaryField\n{\n"
            for patch, text in entries:
                body += f"    {patch}\n    {{\n{text}    }}\n"
            return body + "}\n"

        zero = "        value uniform (0 0 0);\n"
        u = [("inlet", "        type waveVelocity;\n" + zero),
             ("atmosphere", "        type pressureInletOutletVelocity;\n" + zero),
             ("sides", "        type empty;\n")]
        u += [(w, "        type noSlip;\n") for w in walls]
        a = [("inlet", "        type waveAlpha;\n        value uniform 0;\n"),
             ("atmosphere", "        type inletOutlet;\n        inletValue uniform 0;\n"
                            "        value uniform 0;\n"),
             ("sides", "        type empty;\n")]
        a += [(w, "        type zeroGradient;\n") for w in walls]
        p = [("inlet", "        type fixedFluxPressure;\n        value uniform 0;\n"),
             ("atmosphere", "        type totalPressure;\n        p0 uniform 0;\n"),
             ("sides", "        type empty;\n")]
        p += [(w, "        type fixedFluxPressure;\n        value uniform 0;\n") for w in walls]
        if outlet:
            u.append(("outlet", "        type waveVelocity;\n" + zero))
            a.append(("outlet", "        type zeroGradient;\n"))
            p.append(("outlet", "        type fixedFluxPressure;\n        value uniform 0;\n"))
        return {"U": ("volVectorField", "dimensions [0 1 -1 0 0 0 0];\n"
                      "internalField uniform (0 0 0);\n" + bf(u)),
                "alpha.water": ("volScalarField", "dimensions [0 0 0 0 0 0 0];\n"
                                "internalField uniform 0;\n" + bf(a)),
                "p_rgh": ("volScalarField", "dimensions [1 -1 -2 0 0 0 0];\n"
                          "internalField uniform 0;\n" + bf(p))}

    @staticmethod
    def reset(case):
        """Fresh initial fields: ``0.orig`` copied to ``0`` (before ``setFields``)."""
        shutil.rmtree(os.path.join(case, "0"), ignore_errors=True)
        shutil.copytree(os.path.join(case, "0.orig"), os.path.join(case, "0"))


TRANSPORT = """phases (water air);
water
{
    transportModel Newtonian;
    nu 1e-06;
    rho 1000;
}
air
{
    transportModel Newtonian;
    nu 1.48e-05;
    rho 1;
}
sigma 0.07;
"""

FV_SCHEMES = """ddtSchemes { default Euler; }
gradSchemes { default Gauss linear; }
divSchemes
{
    div(rhoPhi,U) Gauss linearUpwind grad(U);
    div(phi,alpha) Gauss vanLeer;
    div(phirb,alpha) Gauss linear;
    div(((rho*nuEff)*dev2(T(grad(U))))) Gauss linear;
}
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
"""

FV_SOLUTION = """solvers
{
    "alpha.water.*"
    {
        nAlphaCorr 1;
        nAlphaSubCycles 1;
        cAlpha 1;
        MULESCorr yes;
        nLimiterIter 5;
        solver smoothSolver;
        smoother symGaussSeidel;
        tolerance 1e-8;
        relTol 0;
    }
    "pcorr.*"
    {
        solver PCG;
        preconditioner DIC;
        tolerance 1e-6;
        relTol 0;
    }
    p_rgh
    {
        solver PCG;
        preconditioner DIC;
        tolerance 1e-6;
        relTol 0.1;
    }
    p_rghFinal
    {
        solver PCG;
        preconditioner DIC;
        tolerance 1e-7;
        relTol 0;
    }
    "U.*"
    {
        solver PBiCG;
        preconditioner DILU;
        tolerance 1e-6;
        relTol 0;
    }
}
PIMPLE
{
    momentumPredictor no;
    nOuterCorrectors 1;
    nCorrectors 2;
    nNonOrthogonalCorrectors 0;
}
"""
